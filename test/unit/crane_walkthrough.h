// The walkthroughs of docs/INTERACTION.md ("## Fold a crane", "## Fold a flapping bird", "## Fold
// a frog base") read as a person reads them: per row of a section's table the steps, the
// gestures they take, and for each fold step the marks it names (`**20**: ... *valley* ×3`), in
// the order of the reference's creases, or the flap it drags (`**7**: press at (0.33, 0.17) ...
// *squash fold*`). The rostests crane_by_mouse, flapping_bird_by_mouse and frog_base_by_mouse
// mark what the text says and count the gestures against it; crane_walkthrough_test and the
// models' tests check the text against the reference scripts.
#pragma once

#include <map>
#include <optional>
#include <regex>
#include <string>
#include <vector>

namespace virtual_origami::test
{
/// A fold step made by dragging a flap (flap mode): where the flap is pressed, in the crease
/// pattern, and the fold the text says the drag makes.
struct FlapDragNamed
{
  double x = 0.0, y = 0.0;
  std::string kind;  // "squash fold", "petal fold", "inside reverse fold", ...
};

/// The flap drag named after `**N**:` (`press at (x, y)` and `*… fold*`), if any.
inline std::optional<FlapDragNamed> flapDragNamed(const std::string& text)
{
  static const std::regex press(R"(press at \(([-0-9.]+), ([-0-9.]+)\))");
  static const std::regex kind(R"(\*((?:squash|petal|inside reverse|outside reverse|reverse) fold)\*)");
  std::smatch p, k;
  if (!std::regex_search(text, p, press) || !std::regex_search(text, k, kind))
    return std::nullopt;
  return FlapDragNamed{ std::stod(p[1]), std::stod(p[2]), k[1] };
}

/// One row of the table: steps `first`–`last`.
struct WalkthroughRow
{
  int first = 0, last = 0;
  int gestures = 0;
  int tool_gestures = -1;                 // with the Fold tool (a `tool` column), -1 when not given
  std::string how;                        // the row's instructions, as written
  std::map<int, std::vector<int>> marks;  // per fold step: +1 valley, −1 mountain, 0 unfold
  std::map<int, FlapDragNamed> drags;     // per fold step made by dragging a flap
};

struct Walkthrough
{
  std::vector<WalkthroughRow> rows;
  int steps = 0;                 // "21 steps" in the text before the table
  int total_gestures = 0;        // "**233 gestures**" there
  int total_tool_gestures = -1;  // "**N gestures with the Fold tool**" there, -1 when not given
  std::string error;             // what could not be read; empty when all was
};

/// The marks named after `**N**:` up to the next step number: *valley*, *mountain*, *unfold*,
/// each once or `×k` times.
inline std::vector<int> marksNamed(const std::string& text)
{
  static const std::regex mark(R"(\*(valley|mountain|unfold)\*(?:\s*×\s*([0-9]+))?)");
  std::vector<int> marks;
  for (auto it = std::sregex_iterator(text.begin(), text.end(), mark); it != std::sregex_iterator(); ++it)
  {
    const std::string kind = (*it)[1];
    const int times = (*it)[2].matched ? std::stoi((*it)[2]) : 1;
    marks.insert(marks.end(), times, kind == "valley" ? 1 : kind == "mountain" ? -1 : 0);
  }
  return marks;
}

/// The walkthrough under the heading `heading` (a whole line, "## Fold a crane"), up to the next
/// heading of its level or above.
inline Walkthrough parseWalkthrough(const std::string& markdown, const std::string& heading)
{
  Walkthrough w;
  size_t section = std::string::npos;
  for (size_t at = markdown.find(heading); at != std::string::npos; at = markdown.find(heading, at + 1))
  {
    const size_t after = at + heading.size();
    if ((at == 0 || markdown[at - 1] == '\n') && (after == markdown.size() || markdown[after] == '\n'))
    {
      section = at;
      break;
    }
  }
  if (section == std::string::npos)
  {
    w.error = "no section \"" + heading + "\"";
    return w;
  }
  // The section ends at the next heading of its level or above (its own "###" parts belong to it).
  const size_t level = heading.find_first_not_of('#');
  size_t end = std::string::npos;
  for (size_t at = markdown.find('\n', section); at != std::string::npos && end == std::string::npos;
       at = markdown.find('\n', at + 1))
  {
    const size_t hashes = markdown.find_first_not_of('#', at + 1);
    if (hashes != std::string::npos && hashes > at + 1 && hashes - (at + 1) <= level && markdown[hashes] == ' ')
      end = at;
  }
  const std::string text = markdown.substr(section, end == std::string::npos ? std::string::npos : end - section);
  std::smatch m;
  if (std::regex_search(text, m, std::regex(R"(([0-9]+) steps,\s*\*\*([0-9]+) gestures\*\*)")))
  {
    w.steps = std::stoi(m[1]);
    w.total_gestures = std::stoi(m[2]);
  }
  else
    w.error = "no \"N steps, **M gestures**\" before the table";
  if (std::regex_search(text, m, std::regex(R"(\*\*([0-9]+) gestures with the Fold tool\*\*)")))
    w.total_tool_gestures = std::stoi(m[1]);
  // | steps | what | gestures | tool (optional) | how |
  static const std::regex row(
      R"(\n\|\s*([0-9]+)(?:–([0-9]+))?\s*\|[^|]*\|\s*([0-9]+)\s*\|(?:\s*([0-9]+)\s*\|)?([^\n]*)\|)");
  static const std::regex step_number(R"(\*\*([0-9]+)\*\*)");
  for (auto it = std::sregex_iterator(text.begin(), text.end(), row); it != std::sregex_iterator(); ++it)
  {
    WalkthroughRow r;
    r.first = std::stoi((*it)[1]);
    r.last = (*it)[2].matched ? std::stoi((*it)[2]) : r.first;
    r.gestures = std::stoi((*it)[3]);
    if ((*it)[4].matched)
      r.tool_gestures = std::stoi((*it)[4]);
    r.how = (*it)[5];
    struct StepNumber
    {
      int step;
      size_t at, after;  // where `**N**` begins, and where its marks begin
    };
    std::vector<StepNumber> numbers;
    for (auto s = std::sregex_iterator(r.how.begin(), r.how.end(), step_number); s != std::sregex_iterator(); ++s)
      numbers.push_back(
          { std::stoi((*s)[1]), static_cast<size_t>(s->position()), static_cast<size_t>(s->position() + s->length()) });
    for (size_t i = 0; i < numbers.size(); ++i)
    {
      const size_t until = i + 1 < numbers.size() ? numbers[i + 1].at : r.how.size();
      const std::string said = r.how.substr(numbers[i].after, until - numbers[i].after);
      if (const std::optional<FlapDragNamed> drag = flapDragNamed(said))
        r.drags[numbers[i].step] = *drag;
      else
        r.marks[numbers[i].step] = marksNamed(said);
    }
    w.rows.push_back(std::move(r));
  }
  if (w.rows.empty() && w.error.empty())
    w.error = "no rows in the table";
  return w;
}

/// docs/INTERACTION.md's "## Fold a crane" (or the walkthrough under `heading`).
inline Walkthrough parseCraneWalkthrough(const std::string& markdown, const std::string& heading = "## Fold a crane")
{
  return parseWalkthrough(markdown, heading);
}

}  // namespace virtual_origami::test
