#include "virtual_origami/ros/interaction_text.h"

#include <cctype>
#include <optional>
#include <regex>
#include <sstream>
#include <utility>
#include <vector>

namespace virtual_origami
{
namespace
{
/// A refusal of fold flat that says where the paper cannot fold (a vertex's rule and the creases
/// to change, or the layers that cannot stack) in the user's words: the ids, which the user does
/// not see, left out; the places on the sheet (crease-pattern points) kept. None for others.
std::optional<std::string> whereItCannotFold(const std::string& message)
{
  const std::string prefix = "do not fold flat: ";
  const size_t at = message.find(prefix);
  if (at == std::string::npos || (message.find(" cannot fold flat: ") == std::string::npos &&
                                  message.find("no order of the layers folds flat") == std::string::npos))
    return std::nullopt;
  std::string text = message.substr(at + prefix.size());
  static const std::vector<std::pair<std::regex, std::string>> names = {
    { std::regex(R"(\bvertex [0-9]+ at )"), "the vertex at " },
    { std::regex(R"(\bcrease [0-9]+ \()"), "the crease (" },
    { std::regex(R"(\bfaces [0-9]+, [0-9]+ and [0-9]+\b)"), "three layers" },
    { std::regex(R"(\bfaces [0-9]+ and [0-9]+\b)"), "two layers" },
    { std::regex(R"(\bface [0-9]+\b)"), "a layer" },
  };
  for (const auto& [id, name] : names)
    text = std::regex_replace(text, id, name);
  return "Not folded: " + text + ".";
}
}  // namespace

std::string forTheUser(const std::string& message)
{
  if (const std::optional<std::string> where = whereItCannotFold(message))
    return *where;
  // Phrases of paper_model's and the drag geometry's messages, and what they mean to someone
  // folding with the mouse.
  static const std::vector<std::pair<std::string, std::string>> known = {
    { "does not cross any face completely", "Not creased: a crease runs across a face from side to side. Draw the line "
                                            "over the whole face." },
    { "runs along an existing edge", "Not creased: there is a crease or an edge there already." },
    { "misses the paper", "Not creased: the line does not cross the paper." },
    { "perpendicular to the face", "Not creased: seen from here the line runs into the paper. Turn the view." },
    { "has no crease to turn about", "This part has no crease to turn about yet: draw one first (Crease mode, "
                                     "right-click menu)." },
    { "no face under the", "Press on the paper to turn a part of it." },
    { "press is on the axis", "Press farther from the crease: the part turns about it." },
    { "lies on neither side of edge", "This part does not turn about the chosen crease. Press next to it, or click off "
                                      "the creases "
                                      "for the automatic axis." },
    { "not a crease to turn about", "That edge is not a crease to turn about." },
    { "past 180 degrees", "Not turned further: the part would pass through the paper beside it." },
    { "could not restore the face shapes", "Not turned: the rest of the paper cannot follow this turn." },
    { "a solver is needed", "Not turned: the rest of the paper cannot follow this turn." },
    { "do not fold flat", "Not folded: the marked creases do not fold flat together (a vertex would tear). Mark the "
                          "creases around it too." },
    { "does not close", "Not folded: the marked creases do not fold flat together (a vertex would tear). Mark the "
                        "creases around it too." },
    { "fixed point lies off the sheet", "Pick the face that stays: click on it, away from the creases." },
    { "bent, paper does not stretch", "The paper cannot reach there even bent: it would have to stretch." },
    { "cannot keep the faces rigid with the pulled", "The paper cannot follow the vertex there without stretching." },
    { "did not answer", "The paper model does not answer: is paper_model running?" },
    { "changed while this was computed", "The paper changed meanwhile: please try again." },
    { "kept changing while this was computed", "The paper changed meanwhile: please try again." },
  };
  for (const auto& [phrase, sentence] : known)
    if (message.find(phrase) != std::string::npos)
      return sentence;
  // Otherwise as it is, without references to the papers ("(seed 000 §3.3)", "Fig. 9").
  std::string text = std::regex_replace(message, std::regex(R"( *\([^()]*\b(seed|Fig\.)[^()]*\))"), "");
  if (!text.empty())
    text[0] = static_cast<char>(std::toupper(static_cast<unsigned char>(text[0])));
  return text;
}

std::string wrapLines(const std::string& text, size_t width)
{
  std::istringstream words(text);
  std::string word, out;
  size_t line = 0;
  while (words >> word)
  {
    if (line > 0 && line + 1 + word.size() > width)
    {
      out += '\n';
      line = 0;
    }
    else if (line > 0)
    {
      out += ' ';
      ++line;
    }
    out += word;
    line += word.size();
  }
  return out;
}

}  // namespace virtual_origami
