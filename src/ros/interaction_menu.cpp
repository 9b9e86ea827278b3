// The interaction's right-click menu: a table of entries, each mapped to what it does (as
// interactive_markers' MenuHandler maps entries to callbacks). Entry texts and their order are
// the menu's interface: scripts and tests choose entries by them and by their ids.
#include <cmath>
#include <map>

#include "virtual_origami/ros/interaction_node.h"

namespace virtual_origami
{
using core::GestureMode;
using core::PaperCommand;
using interactive_markers::MenuHandler;

std::vector<InteractionNode::MenuEntry> InteractionNode::menuEntries()
{
  const auto mode = [this](GestureMode m) {
    return MenuEntry{ "", "", [this, m](const Feedback& f) { model_.chooseMode(m, pointer(f)); },
                      [this, m] { return model_.mode() == m; } };
  };
  const auto command = [this](PaperCommand c) {
    return [this, c](const Feedback& f) { model_.command(c, pointer(f)); };
  };
  const auto foldTo = [this](double fraction) {
    return [this, fraction](const Feedback& f) { model_.foldByAssignment(fraction, pointer(f)); };
  };
  const auto foldMarks = [this](double angle) {
    return [this, angle](const Feedback& f) { model_.foldMarks(angle, pointer(f)); };
  };
  const auto titled = [](MenuEntry entry, const std::string& title) {
    entry.title = title;
    return entry;
  };
  const std::string by_assignment = "Fold by assignment", marked = "Fold on the marked creases";
  return {
    titled(mode(GestureMode::Crease), "Crease mode"),
    titled(mode(GestureMode::Rotate), "Rotate mode"),
    { "Squash", "", command(PaperCommand::Squash), {} },
    { "Undo", "", command(PaperCommand::Undo), {} },
    { "Redo", "", command(PaperCommand::Redo), {} },
    { "Reset", "", command(PaperCommand::Reset), {} },
    { "Pin the nearest vertex", "", [this](const Feedback& f) { model_.pin(pointer(f), false); }, {} },
    { "Release the nearest pin", "", [this](const Feedback& f) { model_.pin(pointer(f), true); }, {} },
    { by_assignment, "", {}, {} },
    { "-100 % (the opposite assignment)", by_assignment, foldTo(-1.0), {} },
    { "0 %", by_assignment, foldTo(0.0), {} },
    { "25 %", by_assignment, foldTo(0.25), {} },
    { "50 %", by_assignment, foldTo(0.5), {} },
    { "75 %", by_assignment, foldTo(0.75), {} },
    { "100 %", by_assignment, foldTo(1.0), {} },
    { "Colour by strain", "",
      [this](const Feedback& f) {
        tell(core::Message{ toggleStrainColours(), rightClick(f) });
      },
      [this] { return colour_by_strain_; } },
    // After the entries above, which keep their places (and ids) in the menu.
    titled(mode(GestureMode::Fold), "Fold mode: mark creases"),
    titled(mode(GestureMode::Drag), "Drag mode: drag a vertex"),
    { marked, "", {}, {} },
    { "Fold flat", marked, foldMarks(M_PI), {} },
    { "Fold to a right angle", marked, foldMarks(M_PI / 2), {} },
    { "Keep the face here", marked, [this](const Feedback& f) { model_.keepFace(pointer(f)); }, {} },
    { "Clear the marks", marked, [this](const Feedback& f) { model_.clearMarks(pointer(f)); }, {} },
    { "Next layer down", "", [this](const Feedback& f) { model_.nextLayer(pointer(f)); }, {} },
    { "Turn the picked layers only", "", [this](const Feedback& f) { model_.togglePickedLayersOnly(pointer(f)); },
      [this] { return model_.pickedLayersOnly(); } },
    { "Snap the line", "", [this](const Feedback& f) { model_.toggleSnapping(pointer(f)); },
      [this] { return model_.snapping(); } },
    { "Keep refused folds by assignment", "", [this](const Feedback& f) { model_.toggleKeepRefusedFolds(pointer(f)); },
      [this] { return model_.keepRefusedFolds(); } },
    titled(mode(GestureMode::Flap), "Flap mode: drag a flap"),
    { "Reverse folds go round the layers", "", [this](const Feedback& f) { model_.toggleOutsideReverse(pointer(f)); },
      [this] { return model_.outsideReverse(); } },
    { "Keep the bend", "", [this](const Feedback& f) { model_.toggleKeepBend(pointer(f)); },
      [this] { return model_.keepBend(); } },
    { "Next layer up", "", [this](const Feedback& f) { model_.previousLayer(pointer(f)); }, {} },
  };
}

void InteractionNode::buildMenu()
{
  std::map<std::string, MenuHandler::EntryHandle> submenus;
  for (MenuEntry& entry : menuEntries())
  {
    // The server's thread only queues the choice; the node's thread carries it out.
    MenuHandler::FeedbackCallback queue;
    if (entry.chosen)
      queue = [this, chosen = entry.chosen](const Feedback::ConstPtr& f) { received(f, chosen); };
    MenuHandler::EntryHandle handle = 0;
    if (entry.submenu.empty())
      handle = queue ? menu_.insert(entry.title, queue) : menu_.insert(entry.title);
    else
      handle = menu_.insert(submenus.at(entry.submenu), entry.title, queue);
    if (!entry.chosen)
      submenus[entry.title] = handle;
    if (entry.checked)
      checkboxes_.emplace_back(handle, entry.checked);
  }
}

void InteractionNode::setCheckMarks()
{
  for (const auto& [handle, checked] : checkboxes_)
    menu_.setCheckState(handle, checked() ? MenuHandler::CHECKED : MenuHandler::UNCHECKED);
  menu_.apply(server_, style_.marker_name);
}

}  // namespace virtual_origami
