// Fuzz target: the readers of text from disk, on any bytes. parseFold (FOLD files, `load`)
// and parsePaperJson (a journal line's state) must never crash, throw or hang, whatever the
// input; what they accept must hold up: a FOLD frame that passes the model's load check loads
// into a session and survives being written and read again, and a journal paper round-trips
// bit for bit.
#include <string>

#include "fuzz_input.h"
#include "virtual_origami/core/fold_io.h"
#include "virtual_origami/core/session.h"
#include "virtual_origami/core/session_journal.h"
#include "virtual_origami/core/validity.h"

using namespace virtual_origami::core;
using virtual_origami::fuzz::fail;

namespace
{
/// What Session::load accepts: other tools round coordinates to about six digits.
const ValidityTolerance kLoadTolerance{ 1e-4, 1e-6, 1e-12 };

void checkFold(const std::string& text)
{
  const Expected<FoldDocument> doc = parseFold(text);
  if (!doc)
  {
    if (doc.message().empty())
      fail("parseFold refused without a message", text);
    return;
  }
  for (size_t i = 0; i < doc->frames.size(); ++i)
  {
    const Paper& frame = doc->frames[i];
    if (!checkValidity(frame, kLoadTolerance).ok())
      continue;  // the session refuses it, with a message (tested in the session target)
    const std::string where = "frame " + std::to_string(i) + ": ";
    // A sheet of another size to load it on: a load of the paper as it is makes no revision
    // (refused, "nothing loaded"), so the fresh unit square would refuse a frame that is one.
    Session session(Paper::square(2.0));
    const Status loaded = session.load(frame, "fuzz.fold");
    if (!loaded && !(frame == session.paper()))
      fail(where + "a valid frame was refused by load: " + loaded.message(), text);
    const std::string written = formatFold(frame, doc->title);
    const Expected<FoldDocument> again = parseFold(written);
    if (!again || again->frames.empty())
      fail(where + "the FOLD written for a valid frame does not parse: " + again.message(), written);
    const Paper& back = again->frames.back();
    if (back.vertices.size() != frame.vertices.size() || back.faces.size() != frame.faces.size() ||
        back.edges.size() != frame.edges.size())
      fail(where + "writing and reading a frame changed its vertices, edges or faces", written);
    const ValidityReport report = checkValidity(back, kLoadTolerance);
    if (!report.ok())
      fail(where + "a valid frame written and read back is not valid: " + report.summary(), written);
  }
}

void checkJournalPaper(const std::string& text)
{
  const Expected<Paper> paper = parsePaperJson(text);
  if (!paper)
  {
    if (paper.message().empty())
      fail("parsePaperJson refused without a message", text);
    return;
  }
  const Expected<Paper> again = parsePaperJson(formatPaperJson(*paper));
  if (!again || !(*again == *paper))
    fail("a journal paper does not round-trip: " + again.message(), text);
}
}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size)
{
  const std::string text(reinterpret_cast<const char*>(data), size);
  checkFold(text);
  checkJournalPaper(text);
  return 0;
}
