#include "breastfit/io/detail/xml_elements.h"

#include "breastfit/core/errors.h"
#include "breastfit/io/detail/text.h"

namespace breastfit::io::detail {
namespace {

bool is_space(char c) { return c == ' ' || c == '\n' || c == '\r' || c == '\t'; }
bool is_name_char(char c) {
  return !is_space(c) && c != '=' && c != '>' && c != '/' && c != '<' && c != '"' && c != '\'';
}

std::string decode_entities(std::string_view v) {
  std::string out;
  out.reserve(v.size());
  for (std::size_t i = 0; i < v.size(); ++i) {
    if (v[i] == '&') {
      static constexpr std::pair<std::string_view, char> kEntities[] = {
          {"&lt;", '<'}, {"&gt;", '>'}, {"&amp;", '&'}, {"&quot;", '"'}, {"&apos;", '\''}};
      bool done = false;
      for (const auto& [entity, c] : kEntities) {
        if (v.substr(i, entity.size()) == entity) {
          out.push_back(c);
          i += entity.size() - 1;
          done = true;
          break;
        }
      }
      if (done) continue;
    }
    out.push_back(v[i]);
  }
  return out;
}

class XmlScanner {
 public:
  XmlScanner(std::string_view text, const std::string& name) : text_(text), name_(name) {}

  XmlDocument read() {
    std::vector<std::size_t> open;
    while (true) {
      const std::size_t lt = text_.find('<', pos_);
      if (lt == std::string_view::npos) break;
      pos_ = lt;
      if (starts("<?")) {
        skip_past("?>", "a '<?' declaration");
      } else if (starts("<!--")) {
        skip_past("-->", "a comment");
      } else if (starts("<!")) {
        skip_past(">", "a '<!' declaration");
      } else if (starts("</")) {
        pos_ += 2;
        const std::string_view tag = read_name();
        skip_space();
        if (!starts(">")) fail("bad end tag </" + ::breastfit::io::detail::quoted(tag) + "");
        if (open.empty() || doc_.elements[open.back()].name != tag) {
          fail("end tag </" + ::breastfit::io::detail::quoted(tag) + "> does not match " +
               (open.empty() ? std::string("any open element")
                             : "<" + ::breastfit::io::detail::quoted(doc_.elements[open.back()].name) + ">"));
        }
        XmlElement& e = doc_.elements[open.back()];
        if (e.children.empty()) e.text = text_.substr(text_begin_[open.back()], lt - text_begin_[open.back()]);
        open.pop_back();
        ++pos_;
      } else {
        ++pos_;
        XmlElement e;
        e.name = std::string(read_name());
        if (e.name.empty()) fail("a '<' not followed by an element name");
        const bool closed = read_attributes(e);
        const std::size_t index = doc_.elements.size();
        if (open.empty() && index > 0) fail("a second root element <" + ::breastfit::io::detail::quoted(e.name) + ">");
        if (!open.empty()) {
          XmlElement& parent = doc_.elements[open.back()];
          // The text before the first child (a DataArray's values before its InformationKeys).
          if (parent.children.empty()) parent.text = text_.substr(text_begin_[open.back()], lt - text_begin_[open.back()]);
          parent.children.push_back(index);
        }
        const bool appended = e.name == "AppendedData";
        doc_.elements.push_back(std::move(e));
        text_begin_.push_back(pos_);
        if (appended) {
          doc_.appended_at = pos_;
          return std::move(doc_);
        }
        if (!closed) {
          if (open.size() >= 64) fail("elements nested more than 64 deep");
          open.push_back(index);
        }
      }
    }
    if (doc_.elements.empty()) fail("no XML element found");
    if (!open.empty()) fail("the file ends inside <" + ::breastfit::io::detail::quoted(doc_.elements[open.back()].name) + ">");
    return std::move(doc_);
  }

 private:
  [[noreturn]] void fail(const std::string& problem) const { throw IoError(name_, problem); }
  bool starts(std::string_view s) const { return text_.substr(pos_, s.size()) == s; }
  void skip_space() {
    while (pos_ < text_.size() && is_space(text_[pos_])) ++pos_;
  }
  void skip_past(std::string_view end, std::string_view what) {
    const std::size_t at = text_.find(end, pos_);
    if (at == std::string_view::npos) fail("the file ends inside " + std::string(what));
    pos_ = at + end.size();
  }
  std::string_view read_name() {
    const std::size_t start = pos_;
    while (pos_ < text_.size() && is_name_char(text_[pos_])) ++pos_;
    return text_.substr(start, pos_ - start);
  }
  /// Reads attributes up to '>' or '/>'; returns true for a self-closing tag.
  bool read_attributes(XmlElement& e) {
    while (true) {
      skip_space();
      if (pos_ >= text_.size()) fail("the file ends inside the tag <" + ::breastfit::io::detail::quoted(e.name) + ">");
      if (starts("/>")) {
        pos_ += 2;
        return true;
      }
      if (starts(">")) {
        ++pos_;
        return false;
      }
      const std::string_view key = read_name();
      skip_space();
      if (key.empty() || !starts("=")) fail("bad attribute in <" + ::breastfit::io::detail::quoted(e.name) + ">");
      ++pos_;
      skip_space();
      if (pos_ >= text_.size() || (text_[pos_] != '"' && text_[pos_] != '\'')) {
        fail("attribute " + ::breastfit::io::detail::quoted(key) + " of <" + ::breastfit::io::detail::quoted(e.name) + "> has no quoted value");
      }
      const char quote = text_[pos_++];
      const std::size_t end = text_.find(quote, pos_);
      if (end == std::string_view::npos) fail("the file ends inside attribute " + ::breastfit::io::detail::quoted(key) + "");
      e.attributes.emplace_back(std::string(key), decode_entities(text_.substr(pos_, end - pos_)));
      pos_ = end + 1;
    }
  }

  std::string_view text_;
  const std::string& name_;
  std::size_t pos_ = 0;
  XmlDocument doc_;
  std::vector<std::size_t> text_begin_;
};

}  // namespace

const std::string* XmlElement::attribute(std::string_view key) const {
  for (const auto& [k, v] : attributes) {
    if (k == key) return &v;
  }
  return nullptr;
}

XmlDocument read_xml_elements(std::string_view text, const std::string& name) {
  return XmlScanner(text, name).read();
}

}  // namespace breastfit::io::detail
