// An SVG element's geometry for the SVG crease-pattern reader: numbers as SVG writes them, the
// transform attribute, and what an element draws as polylines in its own coordinates. Private to
// src/core.
#pragma once

#include <cctype>
#include <charconv>
#include <cmath>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include <Eigen/Geometry>

#include "virtual_origami/core/paper.h"
#include "xml_document.h"

namespace virtual_origami::core
{
/// Reads numbers as SVG writes them: separated by spaces or commas, or by nothing where the next
/// starts with a sign or a second point ("1.5.5-2" is 1.5, .5, -2).
class NumberReader
{
public:
  explicit NumberReader(std::string_view text) : text_(text)
  {}

  void skipSeparators()
  {
    while (pos_ < text_.size() && (std::isspace(static_cast<unsigned char>(text_[pos_])) || text_[pos_] == ','))
      ++pos_;
  }
  bool atEnd()
  {
    skipSeparators();
    return pos_ >= text_.size();
  }
  char peek()
  {
    skipSeparators();
    return pos_ < text_.size() ? text_[pos_] : '\0';
  }
  void skip()
  {
    ++pos_;
  }
  bool atNumber()
  {
    const char c = peek();
    return std::isdigit(static_cast<unsigned char>(c)) || c == '-' || c == '+' || c == '.';
  }
  std::optional<double> number()
  {
    skipSeparators();
    size_t end = pos_;
    if (end < text_.size() && (text_[end] == '+' || text_[end] == '-'))
      ++end;
    bool digits = false, point = false;
    for (; end < text_.size(); ++end)
    {
      const char c = text_[end];
      if (std::isdigit(static_cast<unsigned char>(c)))
        digits = true;
      else if (c == '.' && !point)
        point = true;
      else
        break;
    }
    if (!digits)
      return std::nullopt;
    if (end < text_.size() && (text_[end] == 'e' || text_[end] == 'E'))
    {
      size_t exponent = end + 1;
      if (exponent < text_.size() && (text_[exponent] == '+' || text_[exponent] == '-'))
        ++exponent;
      if (exponent < text_.size() && std::isdigit(static_cast<unsigned char>(text_[exponent])))
      {
        end = exponent;
        while (end < text_.size() && std::isdigit(static_cast<unsigned char>(text_[end])))
          ++end;
      }
    }
    std::string_view token = text_.substr(pos_, end - pos_);
    if (token.front() == '+')
      token.remove_prefix(1);
    double value = 0;
    const auto [stop, error] = std::from_chars(token.data(), token.data() + token.size(), value);
    if (error != std::errc() || stop != token.data() + token.size() || !std::isfinite(value))
      return std::nullopt;
    pos_ = end;
    return value;
  }
  /// An arc's flag: one character, 0 or 1, which may run into what follows ("a1 1 0 01 5 5").
  std::optional<bool> flag()
  {
    const char c = peek();
    if (c != '0' && c != '1')
      return std::nullopt;
    ++pos_;
    return c == '1';
  }

private:
  std::string_view text_;
  size_t pos_ = 0;
};

/// "<path> on line 12", for messages.
std::string describeElement(const XmlElement& element);
/// Refuses (FormatError) with the element named.
[[noreturn]] void failIn(const XmlElement& element, const std::string& message);

using SvgTransform = Eigen::Affine2d;
/// A transform attribute (matrix, translate, scale, rotate, skewX, skewY, applied left to right
/// as SVG composes them); refuses anything else naming the element.
SvgTransform parseTransform(const XmlElement& element, const std::string& text);

using Polyline = std::vector<Vec2>;
/// What `<line>`, `<polyline>`, `<polygon>`, `<rect>`, `<circle>`, `<ellipse>` or `<path>` draws,
/// in its own coordinates (curves and arcs as polylines); nothing for other elements. Refuses
/// malformed geometry naming the element.
std::vector<Polyline> elementPolylines(const XmlElement& element);

}  // namespace virtual_origami::core
