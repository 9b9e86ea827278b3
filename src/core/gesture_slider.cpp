// The gesture model's fold slider: the handle beside the sheet previews a fold by assignment
// while it moves and commits it on release.
#include <algorithm>
#include <cmath>
#include <limits>

#include "virtual_origami/core/gesture_model.h"

namespace virtual_origami::core
{
namespace
{
/// A slider preview within this (rad, RMS) of its fraction has caught up with the handle.
constexpr double kSliderCaughtUp = 2e-4;
/// A preview that came no nearer than this share of the nearest one before it did not come nearer;
/// three such in a row end the catching up: the frames have reached the balance the fraction has
/// (a frame's first steps from a flick may go no nearer).
constexpr double kSliderProgress = 0.99;
constexpr int kSliderStalledFrames = 3;

/// Fractions are committed to 0.1 %: what the percent shows is what is recorded.
double tidy(double fraction)
{
  return std::round(std::clamp(fraction, -1.0, 1.0) * 1000.0) / 1000.0;
}
}  // namespace

void GestureModel::slidePress()
{
  enter(GestureState::Sliding);
  move_pending_ = false;
  fraction_at_press_ = slider_fraction_;
  slider_previewed_.reset();
}

void GestureModel::slideMove(double fraction)
{
  if (state_ != GestureState::Sliding)
    return;
  slider_fraction_ = tidy(fraction);
  slider_moved_at_ = clock_();
  move_pending_ = true;
}

void GestureModel::updateSlider()
{
  move_pending_ = false;
  emit(SliderMoved{ slider_fraction_ });
  // One preview per batch of moves: the call waits for the solver, and the moves that came
  // meanwhile were coalesced into the latest, so previews go as fast as the solver keeps up.
  if (!slider_previewed_ || *slider_previewed_ != slider_fraction_)
  {
    const PaperReply reply = send(FoldByAssignmentCall{ slider_fraction_, true });
    if (reply.success)
    {
      slider_previewed_ = slider_fraction_;
      slider_behind_ = reply.angle_error;
      slider_stalled_ = 0;
    }
  }
  ++updates_;
}

bool GestureModel::catchUpSlider()
{
  if (state_ != GestureState::Sliding || move_pending_ || !slider_previewed_ || *slider_previewed_ != slider_fraction_ ||
      clock_() - slider_moved_at_ < settings_.slider_catch_up_after)
    return false;
  // Each frame is one step of the solver (at 10,000 vertices a tenth of the way): on while they
  // still come nearer, and not past a hundredth of a degree (nothing the eye sees).
  if (!(slider_behind_ > kSliderCaughtUp) || slider_stalled_ >= kSliderStalledFrames)
    return false;
  const PaperReply reply = send(FoldByAssignmentCall{ slider_fraction_, true });
  const double behind = reply.success ? reply.angle_error : std::numeric_limits<double>::quiet_NaN();
  if (behind < kSliderProgress * slider_behind_)
  {
    slider_behind_ = behind;  // the nearest so far
    slider_stalled_ = 0;
  }
  else if (std::isnan(behind))
    slider_behind_ = behind;  // no answer of how far: no more
  else
    ++slider_stalled_;
  return true;
}

void GestureModel::slideRelease(double fraction)
{
  if (state_ != GestureState::Sliding)
    return;
  slider_fraction_ = tidy(fraction);
  move_pending_ = false;
  enter(GestureState::Idle);
  // A press without a move commits nothing; once a preview is drawn, the release commits.
  if (slider_previewed_ || slider_fraction_ != fraction_at_press_)
  {
    const std::string said = commitFold(slider_fraction_);
    if (!said.empty())
      emit(Message{ said, Vec3::Zero(), Message::Place::Slider });
  }
  if (sheet_stale_)
    showSheet();
  if (slider_stale_)
    showSlider();
  else  // rviz keeps the handle where the drag left it; the percent stays with it
    emit(SliderMoved{ slider_fraction_ });
}

void GestureModel::foldByAssignment(double fraction, const Pointer& at)
{
  const std::string said = commitFold(fraction);
  if (!said.empty())
    tell(said, rightClick(at));
}

std::string GestureModel::commitFold(double fraction)
{
  const PaperReply reply = send(FoldByAssignmentCall{ fraction, false, keep_refused_folds_ });
  if (reply.answered && reply.success)
    committed_fraction_ = std::make_pair(reply.revision, fraction);
  return reply.message;
}

}  // namespace virtual_origami::core
