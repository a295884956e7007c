#pragma once
/// \file A minimal XML element reader for VTK XML files (private to the io layer): elements,
/// their attributes and text, comments and declarations skipped. Reading stops at the start tag
/// of `<AppendedData>`, whose content is binary and whose position is returned.
#include <cstddef>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace breastfit::io::detail {

/// One element: name, attributes (entities &lt; &gt; &amp; &quot; &apos; decoded), children
/// (indices into XmlDocument::elements) and its text before the first child (all of it for an
/// element without children).
struct XmlElement {
  std::string name;
  std::vector<std::pair<std::string, std::string>> attributes;
  std::vector<std::size_t> children;
  std::string_view text;

  /// The value of attribute `key`, or nullptr.
  const std::string* attribute(std::string_view key) const;
};

/// The elements of a document, the root first.
struct XmlDocument {
  std::vector<XmlElement> elements;
  /// Position in the text just after `<AppendedData …>`, or npos when there is none.
  std::size_t appended_at = std::string_view::npos;
};

/// Reads the elements of `text`.
/// \throws IoError(name, problem) for a malformed document (unclosed tag, mismatched end tag,
///         bad attribute, no root element)
XmlDocument read_xml_elements(std::string_view text, const std::string& name);

}  // namespace breastfit::io::detail
