#!/usr/bin/env python3
"""Writes blender_box.gltf: a tiny rig laid out the way Blender's glTF exporter (3.x, "glTF
Embedded", +Y up) writes one: an "Armature" node holding the bone nodes (with bone-orientation
rotations) and the skinned mesh node, inverse bind matrices at the bind pose, JOINTS_0 as
UNSIGNED_BYTE, WEIGHTS_0 as float (one vertex's weights not summing to 1), morph targets with
POSITION and NORMAL deltas named in mesh.extras.targetNames (the second one as a sparse
accessor), a material, TEXCOORD_0, and one vertex split at a UV seam (same position, weights and
morph deltas, different UV). No breastfit extras. The Khronos validator reports exactly the two
deliberate oddities: the skinned mesh node is not a scene root (Blender parents it to the
armature) and vertex 5's weights sum to 0.95.

Geometry (metres, glTF frame): a box x in [-0.1, 0.1], y in [0, 0.4], z in [-0.05, 0.05].
Bones: "Spine" at the origin rotated 10 degrees about +Z; "Chest" its child at local (0, 0.2, 0).
Run: python3 make_blender_box.py  (writes next to itself).
"""
import base64, json, math, os, struct

V = [(-0.1, 0.0, -0.05), (0.1, 0.0, -0.05), (0.1, 0.0, 0.05), (-0.1, 0.0, 0.05),
     (-0.1, 0.4, -0.05), (0.1, 0.4, -0.05), (0.1, 0.4, 0.05), (-0.1, 0.4, 0.05)]
V.append(V[6])  # vertex 8: UV-seam copy of vertex 6
UV = [(0, 0), (1, 0), (1, 1), (0, 1), (0, 0), (1, 0), (1, 1), (0, 1), (0.5, 0.5)]
# Outward counter-clockwise faces (vertex 8 used in the top face instead of 6).
F = [(0, 1, 2), (0, 2, 3),          # bottom (-y)
     (4, 7, 8), (4, 8, 5),          # top (+y)
     (0, 4, 5), (0, 5, 1),          # back (-z)
     (3, 2, 6), (3, 6, 7),          # front (+z)
     (0, 3, 7), (0, 7, 4),          # left (-x)
     (1, 5, 6), (1, 6, 2)]          # right (+x)
N = [(0.0, 1.0 if v[1] > 0.2 else -1.0, 0.0) for v in V]
J = [(0, 0, 0, 0)] * 4 + [(0, 1, 0, 0)] * 5
W = [(1.0, 0, 0, 0)] * 4 + [(0.3, 0.7, 0, 0), (0.25, 0.7, 0, 0), (0.3, 0.7, 0, 0), (0.3, 0.7, 0, 0), (0.3, 0.7, 0, 0)]
# Morph "Key 1": top vertices forward (+z) by 1 cm; "Breast": vertex 6 (and its copy 8) forward 5 cm.
KEY1 = [(0, 0, 0)] * 4 + [(0, 0, 0.01)] * 5
BREAST_IDX = [6, 8]
BREAST_VAL = [(0.0, 0.0, 0.05), (0.0, 0.0, 0.05)]

buf = bytearray()
views, accessors = [], []

def add_view(data, target=None):
    while len(buf) % 4:
        buf.append(0)
    off = len(buf)
    buf.extend(data)
    v = {"buffer": 0, "byteOffset": off, "byteLength": len(data)}
    if target:
        v["target"] = target
    views.append(v)
    return len(views) - 1

def add_acc(fmt, rows, ctype, typ, target=34962, minmax=False):
    data = b"".join(struct.pack("<" + fmt, *r) for r in rows)
    a = {"bufferView": add_view(data, target), "componentType": ctype, "count": len(rows), "type": typ}
    if minmax:
        a["min"] = [min(r[c] for r in rows) for c in range(len(rows[0]))]
        a["max"] = [max(r[c] for r in rows) for c in range(len(rows[0]))]
    accessors.append(a)
    return len(accessors) - 1

pos = add_acc("3f", V, 5126, "VEC3", minmax=True)
nrm = add_acc("3f", N, 5126, "VEC3")
tex = add_acc("2f", UV, 5126, "VEC2")
jnt = add_acc("4B", J, 5121, "VEC4")
wgt = add_acc("4f", W, 5126, "VEC4")
idx = add_acc("H", [(i,) for f in F for i in f], 5123, "SCALAR", target=34963)
k1p = add_acc("3f", KEY1, 5126, "VEC3", minmax=True)
k1n = add_acc("3f", [(0, 0, 0)] * len(V), 5126, "VEC3")
# Sparse morph target: no bufferView, sparse indices + values.
iv = add_view(struct.pack("<2I", *BREAST_IDX))
vv = add_view(b"".join(struct.pack("<3f", *r) for r in BREAST_VAL))
accessors.append({"componentType": 5126, "count": len(V), "type": "VEC3",
                  "min": [0, 0, 0], "max": [0, 0, 0.05],
                  "sparse": {"count": 2, "indices": {"bufferView": iv, "componentType": 5125},
                             "values": {"bufferView": vv}}})
brp = len(accessors) - 1
brn = add_acc("3f", [(0, 0, 0)] * len(V), 5126, "VEC3")

a = math.radians(10.0)
spine_q = [0.0, 0.0, math.sin(a / 2), math.cos(a / 2)]
# World matrices: Spine = Rz(10deg); Chest = Spine * T(0, 0.2, 0).  IBM = inverse(world).
c, s = math.cos(a), math.sin(a)
def mat_cm(R, t):  # column-major 4x4 from 3x3 rows R and translation t
    return [R[0][0], R[1][0], R[2][0], 0, R[0][1], R[1][1], R[2][1], 0, R[0][2], R[1][2], R[2][2], 0, t[0], t[1], t[2], 1]
Rt = [[c, s, 0], [-s, c, 0], [0, 0, 1]]  # inverse rotation
chest_world_t = (-s * 0.2, c * 0.2, 0.0)
ibm_spine = mat_cm(Rt, (0, 0, 0))
inv_t = [-(Rt[r][0] * chest_world_t[0] + Rt[r][1] * chest_world_t[1] + Rt[r][2] * chest_world_t[2]) for r in range(3)]
ibm_chest = mat_cm(Rt, inv_t)
ibm = add_acc("16f", [ibm_spine, ibm_chest], 5126, "MAT4", target=None)

gltf = {
    "asset": {"generator": "Khronos glTF Blender I/O v3.6.27", "version": "2.0"},
    "scene": 0,
    "scenes": [{"name": "Scene", "nodes": [3]}],
    "nodes": [
        {"mesh": 0, "name": "Body", "skin": 0},
        {"name": "Spine", "rotation": spine_q, "children": [2]},
        {"name": "Chest", "translation": [0.0, 0.2, 0.0]},
        {"name": "Armature", "children": [0, 1]},
    ],
    "materials": [{"doubleSided": True, "name": "Skin",
                   "pbrMetallicRoughness": {"baseColorFactor": [0.8, 0.6, 0.5, 1.0], "metallicFactor": 0, "roughnessFactor": 0.5}}],
    "meshes": [{
        "name": "Body",
        "extras": {"targetNames": ["Key 1", "Breast"]},
        "weights": [0.0, 0.0],
        "primitives": [{
            "attributes": {"POSITION": pos, "NORMAL": nrm, "TEXCOORD_0": tex, "JOINTS_0": jnt, "WEIGHTS_0": wgt},
            "indices": idx, "material": 0,
            "targets": [{"POSITION": k1p, "NORMAL": k1n}, {"POSITION": brp, "NORMAL": brn}],
        }],
    }],
    "skins": [{"inverseBindMatrices": ibm, "joints": [1, 2], "name": "Armature"}],
    "accessors": accessors,
    "bufferViews": views,
    "buffers": [{"byteLength": len(buf),
                 "uri": "data:application/octet-stream;base64," + base64.b64encode(bytes(buf)).decode()}],
}
out = os.path.join(os.path.dirname(os.path.abspath(__file__)), "blender_box.gltf")
with open(out, "w") as f:
    json.dump(gltf, f, indent=1)
print("wrote", out)
