// A small XML reader for the SVG crease-pattern reader: elements, their attributes (entities
// decoded) and their text, with the line each starts on. No namespaces, no DTD (a DOCTYPE and
// its internal subset are skipped, entities it declares stay as written). Private to src/core.
#pragma once

#include <string>
#include <utility>
#include <vector>

#include "virtual_origami/core/result.h"

namespace virtual_origami::core
{
struct XmlElement
{
  std::string name;  // as written, prefix included ("svg:path")
  std::vector<std::pair<std::string, std::string>> attributes;
  std::vector<XmlElement> children;
  std::string text;  // the character data directly inside it, CDATA included
  int line = 0;

  /// The attribute's value, or nullptr.
  const std::string* attribute(const std::string& key) const;
  /// The name without its namespace prefix.
  std::string localName() const;
};

/// The document's root element. Refuses, naming the line, a tag never closed, a closing tag that
/// does not match, an attribute without a quoted value, text outside the root, and nesting deeper
/// than `max_depth`. Messages never quote the text.
Expected<XmlElement> parseXml(const std::string& text, int max_depth = 256);

}  // namespace virtual_origami::core
