// fold_sequence: turns a fold-sequence file into a recording and pictures of every step.
//   fold_sequence SEQUENCE.json [--out DIR]
// writes DIR/NAME.bag (operations and states, as the recorder would, replayable with
// launch/replay.launch), DIR/NAME.fold (one frame per step), DIR/NAME.obj (the result) and
// DIR/NAME_frames/NNN.svg (+ .png where rsvg-convert is installed).
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>

#include <ros/time.h>

#include "virtual_origami/core/fold_io.h"
#include "virtual_origami/core/fold_sequence.h"
#include "virtual_origami/core/obj_export.h"
#include "virtual_origami/core/svg.h"
#include "virtual_origami/ros/conversions.h"
#include "virtual_origami/ros/recording.h"
#include "virtual_origami/solvers/solver_factory.h"

using namespace virtual_origami;

namespace
{
int fail(const std::string& message)
{
  std::fprintf(stderr, "fold_sequence: %s\n", message.c_str());
  return 1;
}

/// Operations one second apart, each followed by the state it made, like a live recording.
core::Status writeBag(const std::string& path, const core::Session& session, const std::vector<core::Paper>& states)
{
  std::filesystem::remove(path);
  DurableBagWriter writer(path);
  ros::Time t(1.0);
  PaperState first = toMessage(states.front(), 0, {});
  first.header.stamp = t;
  first.header.frame_id = "paper";
  core::Status s = writer.write("/origami/state", first);
  const auto& log = session.log();
  for (size_t i = 0; s && i < log.size(); ++i)
  {
    t += ros::Duration(1.0);
    Operation op = toMessage(log[i], &states[i + 1]);
    op.header.stamp = t;
    op.header.frame_id = "paper";
    s = writer.write("/origami/operations", op);
    PaperState state = toMessage(states[i + 1], log[i].revision, {});
    state.header = op.header;
    if (s)
      s = writer.write("/origami/state", state);
  }
  return s;
}
}  // namespace

int main(int argc, char** argv)
{
  if (argc < 2)
    return fail("usage: fold_sequence SEQUENCE.json [--out DIR]");
  std::string out = "output";
  for (int i = 2; i + 1 < argc; ++i)
    if (std::strcmp(argv[i], "--out") == 0)
      out = argv[i + 1];
  std::ifstream in(argv[1]);
  if (!in)
    return fail(std::string("cannot open ") + argv[1]);
  std::stringstream text;
  text << in.rdbuf();
  const auto sequence = core::parseFoldSequence(text.str());
  if (!sequence)
    return fail(std::string(argv[1]) + ": " + sequence.message());
  core::Session session;
  // The sequence starts with a reset, the session's first logged operation: frames[i] is the
  // state after log[i].
  const auto states = core::foldSequence(*sequence, session, core::makeSolver(sequence->solver));
  if (!states)
    return fail(std::string(argv[1]) + ": " + states.message());
  std::vector<core::Paper> frames(states->begin(), states->end());

  ros::Time::init();
  const std::string name = std::filesystem::path(argv[1]).stem().string();
  const std::string base = out + "/" + name;
  std::filesystem::create_directories(base + "_frames");
  std::vector<core::Paper> with_start{ core::Paper::square(sequence->size) };
  with_start.insert(with_start.end(), frames.begin(), frames.end());
  for (const core::Status& s :
       { core::writeTextFile(base + ".fold", core::formatFoldSequence(frames, sequence->title)),
         core::writeTextFile(base + ".obj", core::formatObj(frames.back())),
         writeBag(base + ".bag", session, with_start) })
    if (!s)
      return fail(s.message());
  std::vector<std::string> notes{ "start" };  // one per frame
  for (const core::FoldStep& step : sequence->steps)
    notes.insert(notes.end(), step.repeat, step.note);
  const bool png = std::system("command -v rsvg-convert >/dev/null 2>&1") == 0;
  for (size_t i = 0; i < frames.size(); ++i)
  {
    char frame[32];
    std::snprintf(frame, sizeof frame, "%03zu", i);
    const std::string svg = base + "_frames/" + frame + ".svg";
    const std::string& note = notes[i];
    const core::Status s = core::writeTextFile(svg, core::paperSvg(frames[i], std::string(frame) + " " + note));
    if (!s)
      return fail(s.message());
    if (png && std::system(("rsvg-convert '" + svg + "' -o '" + base + "_frames/" + frame + ".png'").c_str()) != 0)
      return fail("rsvg-convert failed on " + svg);
  }
  std::printf("%s: %zu steps -> %s.bag, %s.fold, %s.obj, %s_frames/ (%s)\n", name.c_str(), sequence->steps.size(),
              base.c_str(), base.c_str(), base.c_str(), base.c_str(), png ? "SVG and PNG" : "SVG");
  return 0;
}
