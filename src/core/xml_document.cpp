#include "xml_document.h"

#include <algorithm>
#include <cctype>
#include <cstdint>
#include <string_view>

#include "format_error.h"

namespace virtual_origami::core
{
const std::string* XmlElement::attribute(const std::string& key) const
{
  for (const auto& [name, value] : attributes)
    if (name == key)
      return &value;
  return nullptr;
}

std::string XmlElement::localName() const
{
  const size_t colon = name.find(':');
  return colon == std::string::npos ? name : name.substr(colon + 1);
}

namespace
{
[[noreturn]] void failAt(int line, const std::string& message)
{
  fail("line " + std::to_string(line) + ": " + message);
}

bool isSpace(char c)
{
  return std::isspace(static_cast<unsigned char>(c)) != 0;
}

void appendUtf8(std::string& out, std::uint32_t code)
{
  if (code < 0x80)
    out += static_cast<char>(code);
  else if (code < 0x800)
  {
    out += static_cast<char>(0xC0 | (code >> 6));
    out += static_cast<char>(0x80 | (code & 0x3F));
  }
  else if (code < 0x10000)
  {
    out += static_cast<char>(0xE0 | (code >> 12));
    out += static_cast<char>(0x80 | ((code >> 6) & 0x3F));
    out += static_cast<char>(0x80 | (code & 0x3F));
  }
  else
  {
    out += static_cast<char>(0xF0 | (code >> 18));
    out += static_cast<char>(0x80 | ((code >> 12) & 0x3F));
    out += static_cast<char>(0x80 | ((code >> 6) & 0x3F));
    out += static_cast<char>(0x80 | (code & 0x3F));
  }
}

/// The five predefined entities and character references decoded; any other entity (declared in
/// a DTD this reader skips) stays as written.
std::string decode(std::string_view raw)
{
  std::string out;
  for (size_t i = 0; i < raw.size(); ++i)
  {
    const size_t semicolon = raw[i] == '&' ? raw.find(';', i) : std::string_view::npos;
    if (semicolon == std::string_view::npos || semicolon - i > 12)
    {
      out += raw[i];
      continue;
    }
    const std::string_view name = raw.substr(i + 1, semicolon - i - 1);
    static const std::pair<const char*, char> named[] = {
      { "lt", '<' }, { "gt", '>' }, { "amp", '&' }, { "quot", '"' }, { "apos", '\'' }
    };
    bool done = false;
    for (const auto& [key, c] : named)
      if (name == key)
      {
        out += c;
        done = true;
      }
    if (!done && name.size() > 1 && name[0] == '#')
    {
      const bool hex = name[1] == 'x' || name[1] == 'X';
      const std::string digits(name.substr(hex ? 2 : 1));
      char* end = nullptr;
      const unsigned long code = std::strtoul(digits.c_str(), &end, hex ? 16 : 10);
      if (!digits.empty() && end && *end == '\0' && code > 0 && code <= 0x10FFFF)
      {
        appendUtf8(out, static_cast<std::uint32_t>(code));
        done = true;
      }
    }
    if (!done)
    {
      out += raw[i];
      continue;
    }
    i = semicolon;
  }
  return out;
}

void readAttributes(std::string_view body, int line, XmlElement& element)
{
  for (size_t i = 0; i < body.size();)
  {
    if (isSpace(body[i]))
    {
      ++i;
      continue;
    }
    size_t j = i;
    while (j < body.size() && body[j] != '=' && !isSpace(body[j]))
      ++j;
    const std::string key(body.substr(i, j - i));
    while (j < body.size() && isSpace(body[j]))
      ++j;
    if (j >= body.size() || body[j] != '=')
      failAt(line, "an attribute without a value");
    ++j;
    while (j < body.size() && isSpace(body[j]))
      ++j;
    if (j >= body.size() || (body[j] != '"' && body[j] != '\''))
      failAt(line, "an attribute value without quotes");
    const size_t close = body.find(body[j], j + 1);
    if (close == std::string_view::npos)
      failAt(line, "an attribute value without its closing quote");
    element.attributes.emplace_back(key, decode(body.substr(j + 1, close - j - 1)));
    i = close + 1;
  }
}

XmlElement parse(const std::string& text, int max_depth)
{
  std::vector<XmlElement> open;  // open[0] is a holder for the root
  open.emplace_back();
  int line = 1;
  size_t pos = text.compare(0, 3, "\xEF\xBB\xBF") == 0 ? 3 : 0;  // a UTF-8 byte-order mark
  const auto advance = [&](size_t to) {
    line += static_cast<int>(std::count(text.begin() + static_cast<std::ptrdiff_t>(pos),
                                        text.begin() + static_cast<std::ptrdiff_t>(to), '\n'));
    pos = to;
  };
  const auto addText = [&](std::string_view chunk, bool raw) {
    if (open.size() > 1)
      open.back().text += raw ? std::string(chunk) : decode(chunk);
    else if (std::any_of(chunk.begin(), chunk.end(), [](char c) { return !isSpace(c); }))
      failAt(line, "text outside the root element");
  };
  while (pos < text.size())
  {
    const size_t lt = text.find('<', pos);
    const size_t text_end = lt == std::string::npos ? text.size() : lt;
    addText(std::string_view(text).substr(pos, text_end - pos), false);
    advance(text_end);
    if (lt == std::string::npos)
      break;
    const int tag_line = line;
    const auto skipPast = [&](const char* terminator, const char* what) {
      const size_t end = text.find(terminator, lt);
      if (end == std::string::npos)
        failAt(tag_line, std::string(what) + " is never closed");
      advance(end + std::char_traits<char>::length(terminator));
    };
    if (text.compare(lt, 4, "<!--") == 0)
    {
      skipPast("-->", "a comment");
      continue;
    }
    if (text.compare(lt, 9, "<![CDATA[") == 0)
    {
      const size_t end = text.find("]]>", lt);
      if (end != std::string::npos)
        addText(std::string_view(text).substr(lt + 9, end - lt - 9), true);
      skipPast("]]>", "a CDATA section");
      continue;
    }
    if (text.compare(lt, 2, "<?") == 0)
    {
      skipPast("?>", "a processing instruction");
      continue;
    }
    if (text.compare(lt, 2, "<!") == 0)
    {
      // A DOCTYPE may hold an internal subset in brackets, with '>' inside.
      const size_t bracket = text.find('[', lt), close = text.find('>', lt);
      if (bracket != std::string::npos && close != std::string::npos && bracket < close)
        skipPast("]>", "a DOCTYPE");
      else
        skipPast(">", "a declaration");
      continue;
    }
    size_t gt = lt + 1;
    for (char quote = 0; gt < text.size(); ++gt)
    {
      const char c = text[gt];
      if (quote)
        quote = c == quote ? 0 : quote;
      else if (c == '"' || c == '\'')
        quote = c;
      else if (c == '>')
        break;
    }
    if (gt >= text.size())
      failAt(tag_line, "a tag is never closed");
    std::string_view body = std::string_view(text).substr(lt + 1, gt - lt - 1);
    advance(gt + 1);
    if (!body.empty() && body.front() == '/')
    {
      body.remove_prefix(1);
      while (!body.empty() && isSpace(body.back()))
        body.remove_suffix(1);
      if (open.size() < 2 || open.back().name != body)
        failAt(tag_line, open.size() < 2 ? "a closing tag with nothing open" :
                                           "a closing tag that does not match the element opened on line " +
                                               std::to_string(open.back().line));
      XmlElement closed = std::move(open.back());
      open.pop_back();
      open.back().children.push_back(std::move(closed));
      continue;
    }
    const bool self_closing = !body.empty() && body.back() == '/';
    if (self_closing)
      body.remove_suffix(1);
    size_t name_end = 0;
    while (name_end < body.size() && !isSpace(body[name_end]))
      ++name_end;
    XmlElement element;
    element.name = std::string(body.substr(0, name_end));
    element.line = tag_line;
    if (element.name.empty())
      failAt(tag_line, "a tag without a name");
    readAttributes(body.substr(name_end), tag_line, element);
    if (open.size() == 1 && !open[0].children.empty())
      failAt(tag_line, "a second root element");
    if (self_closing)
      open.back().children.push_back(std::move(element));
    else
    {
      if (static_cast<int>(open.size()) > max_depth)
        failAt(tag_line, "elements nested more than " + std::to_string(max_depth) + " deep");
      open.push_back(std::move(element));
    }
  }
  if (open.size() > 1)
    failAt(open.back().line, "an element opened here is never closed");
  if (open[0].children.empty())
    fail("no XML element");
  return std::move(open[0].children.front());
}

}  // namespace

Expected<XmlElement> parseXml(const std::string& text, int max_depth)
{
  return guarded<XmlElement>([&] { return parse(text, max_depth); });
}

}  // namespace virtual_origami::core
