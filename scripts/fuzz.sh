#!/usr/bin/env bash
# Builds the libFuzzer harnesses for the mesh readers in build-fuzz (clang, ASan + UBSan) and runs
# each for N seconds on a seed corpus made from the test fixtures.
# Usage: scripts/fuzz.sh [SECONDS=180] [FORMAT...]     (formats: ply obj stl vtk vtp; default all)
# Crashes, hangs and over-limit allocations are written to build-fuzz/artifacts/<format>/; copy a
# fixed crasher to tests/data/fuzz/<format>/ so malformed_mesh_test replays it.
set -euo pipefail

here="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
seconds="${1:-180}"
shift || true
formats=("$@")
[ ${#formats[@]} -eq 0 ] && formats=(ply obj stl vtk vtp)
build="$here/build-fuzz"

command -v clang++ >/dev/null || { echo "fuzz.sh: clang++ not found (apt-get install clang)" >&2; exit 1; }
cmake -S "$here" -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo -DCMAKE_CXX_COMPILER=clang++ \
  -DBREASTFIT_BUILD_FUZZ=ON -DBREASTFIT_BUILD_TESTS=OFF -DBREASTFIT_BUILD_BENCH=OFF \
  -DBREASTFIT_BUILD_CLI=OFF >/dev/null
cmake --build "$build" --target fuzzers -j2

# Seed corpus: the hand-written fixtures, the kept regressions, and a few binary files generated
# here (binary PLY in both byte orders, binary STL whose header starts with "solid").
corpus="$build/corpus"
mkdir -p "$corpus"/{ply,obj,stl,vtk,vtp}
for f in ply obj stl vtk vtp; do
  find "$here/tests/data/meshes" -maxdepth 1 -iname "*.$f" -exec cp {} "$corpus/$f/" \;
  if [ -d "$here/tests/data/fuzz/$f" ]; then
    find "$here/tests/data/fuzz/$f" -maxdepth 1 -type f ! -name '.*' -exec cp {} "$corpus/$f/" \;
  fi
done
/usr/bin/python3 - "$corpus" <<'PY'
import struct, sys, pathlib
out = pathlib.Path(sys.argv[1])
verts = [(0, 0, 0), (1, 0, 0), (1, 1, 0), (0, 1, 0.5)]
for order, tag in (("<", "little"), (">", "big")):
    head = ("ply\nformat binary_%s_endian 1.0\nelement vertex 4\nproperty float x\nproperty float y\n"
            "property double z\nproperty uchar red\nproperty uchar green\nproperty uchar blue\n"
            "element face 2\nproperty list uchar int vertex_indices\nproperty list ushort short junk\n"
            "end_header\n" % tag).encode()
    body = b"".join(struct.pack(order + "ffdBBB", x, y, z, 10, 20, 30) for x, y, z in verts)
    body += struct.pack(order + "B3iH", 3, 0, 1, 2, 0) + struct.pack(order + "B4iHh", 4, 0, 2, 3, 1, 1, -7)
    (out / "ply" / ("seed_binary_%s.ply" % tag)).write_bytes(head + body)
tris = [(0, 1, 2), (0, 2, 3)]
stl = b"solid looks ascii".ljust(80, b" ") + struct.pack("<I", len(tris))
for t in tris:
    stl += struct.pack("<3f", 0, 0, 1) + b"".join(struct.pack("<3f", *verts[i]) for i in t) + b"\0\0"
(out / "stl" / "seed_binary.stl").write_bytes(stl)
import zlib
pts = [0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0.5]
vtk = b"# vtk DataFile Version 5.1\nseed SPACE=RAS\nBINARY\nDATASET POLYDATA\nPOINTS 4 float\n"
vtk += struct.pack(">12f", *pts) + b"\nPOLYGONS 3 7\nOFFSETS vtktypeint64\n" + struct.pack(">3q", 0, 4, 7)
vtk += b"\nCONNECTIVITY vtktypeint64\n" + struct.pack(">7q", 0, 1, 2, 3, 0, 1, 2) + b"\n"
(out / "vtk" / "seed_binary.vtk").write_bytes(vtk)
def zblock(raw):
    z = zlib.compress(raw)
    return struct.pack("<4I", 1, len(raw), len(raw), len(z)) + z
arrays = [zblock(struct.pack("<12f", *pts)), zblock(struct.pack("<7q", 0, 1, 2, 3, 0, 1, 2)), zblock(struct.pack("<2q", 4, 7))]
offsets = [0, len(arrays[0]), len(arrays[0]) + len(arrays[1])]
vtp = ('<VTKFile type="PolyData" version="1.0" byte_order="LittleEndian" header_type="UInt32" '
       'compressor="vtkZLibDataCompressor"><PolyData><Piece NumberOfPoints="4" NumberOfPolys="2"><Points>'
       '<DataArray type="Float32" NumberOfComponents="3" format="appended" offset="%d"/></Points><Polys>'
       '<DataArray type="Int64" Name="connectivity" format="appended" offset="%d"/>'
       '<DataArray type="Int64" Name="offsets" format="appended" offset="%d"/></Polys></Piece></PolyData>'
       '<AppendedData encoding="raw">_' % tuple(offsets)).encode()
(out / "vtp" / "seed_zlib.vtp").write_bytes(vtp + b"".join(arrays) + b"</AppendedData></VTKFile>\n")
PY

status=0
for f in "${formats[@]}"; do
  artifacts="$build/artifacts/$f"
  mkdir -p "$artifacts" "$build/work/$f"
  cp -n "$corpus/$f"/* "$build/work/$f/" 2>/dev/null || true
  echo "== fuzz_$f for ${seconds}s"
  log="$build/fuzz_$f.log"
  if ! "$build/fuzz/fuzz_$f" "$build/work/$f" -dict="$here/fuzz/$f.dict" -max_total_time="$seconds" \
      -rss_limit_mb=512 -malloc_limit_mb=256 -timeout=5 -max_len=16384 -print_final_stats=1 \
      -artifact_prefix="$artifacts/" >"$log" 2>&1; then
    status=1
    echo "fuzz_$f: FOUND A PROBLEM, see $log and $artifacts" >&2
  fi
  grep -E "stat::number_of_executed_units|stat::peak_rss_mb" "$log" | tr '\n' ' '
  echo
done
exit $status
