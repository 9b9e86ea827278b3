// Flap mode: a fold by one drag (compound_fold.h under the mouse). The press works out the folds
// the pressed flap can make; each update previews the one whose way (the pressed point's) the
// pointer is on, as far along as the pointer is; the release commits it flat.
#include <algorithm>
#include <cctype>
#include <chrono>
#include <cmath>

#include "virtual_origami/core/gesture_model.h"
#include "virtual_origami/core/layer_pick.h"

namespace virtual_origami::core
{
namespace
{
/// A release this far from where the fold takes the pressed point, of the way there, folds
/// nothing: the pointer is nearer the press than the fold.
constexpr double kMissedFold = 0.5;
/// Folds whose directions the press works out, at most (each a flat fold or a few), and for how
/// long at most: a press where many folds meet (a frog base's closed point) stays within a frame.
constexpr size_t kResolvedAtPress = 64;
constexpr std::chrono::milliseconds kResolvingAtPress(10);
}  // namespace

void GestureModel::pressFlap()
{
  flap_.reset();
  flap_refusal_.clear();
  flap_previewed_.reset();
  const Vec3 view = sight(press_camera_, press_);
  // A layer picked here (Next layer down) is pressed instead of the top one.
  int face = pickedHere(Pick::Kind::Face, press_) ? pick_.current() : -1;
  if (face < 0)
  {
    const std::vector<int> under = facesUnder(*paper_, press_, view);
    face = under.empty() ? -1 : under[0];
  }
  if (face < 0)
  {
    flap_refusal_ = "No paper here: press on a flap and drag it where it should lie.";
    return;
  }
  Expected<CompoundFolds> folds = CompoundFolds::at(*paper_, face, press_, -view);
  if (!folds)
    flap_refusal_ = "Not folded: " + folds.message() + ".";
  else if (folds->outcomes().empty())
    flap_refusal_ = "This flap folds no other way flat along the creases there: crease it first.";
  else
  {
    // Their fold directions now, while the press is still: the previews then only ask for
    // frames (of many folds, the rest when the pointer first comes near them).
    const auto until = std::chrono::steady_clock::now() + kResolvingAtPress;
    for (size_t i = 0; i < std::min(folds->outcomes().size(), kResolvedAtPress); ++i)
    {
      folds->resolve(i);
      if (std::chrono::steady_clock::now() > until)
        break;
    }
    flap_ = std::move(*folds);
  }
}

std::pair<const FlatFoldRequest*, CompoundKind> GestureModel::flapFold(const CompoundFolds::Resolved& fold) const
{
  if (outside_reverse_ && fold.outside)
    return { &*fold.outside, CompoundKind::OutsideReverse };
  return { &fold.request, fold.kind };
}

void GestureModel::toggleOutsideReverse(const Pointer& at)
{
  outside_reverse_ = !outside_reverse_;
  showSheet();  // the menu's check mark
  tell(outside_reverse_ ? "A flap dragged over a line wraps its tip round the layers (an outside reverse fold)." :
                          "A flap dragged over a line turns its tip in between the layers (an inside reverse fold).",
       rightClick(at));
}

Vec3 GestureModel::flapTarget() const
{
  if (!pointer_camera_)
    return pointer_;
  // Where the pointer's sight line meets the plane the paper lies in.
  return alongSightOnto(*pointer_camera_, pointer_, press_, Vec3::UnitZ()).value_or(pointer_);
}

void GestureModel::updateFlap()
{
  if (!flap_)
    return;
  const auto chosen = flap_->nearestResolved(flapTarget());
  if (!chosen)
    return;
  const auto& [choice, fold] = *chosen;
  if (flap_previewed_ && flap_previewed_->first == choice.outcome &&
      std::abs(flap_previewed_->second - choice.fraction) < 1e-3)
    return;
  if (!flap_previewed_ && choice.fraction < 1e-3)
    return;  // nothing to show yet
  if (send(FlatFoldCall{ *flapFold(fold).first, choice.fraction, false }).success)
    flap_previewed_ = std::make_pair(choice.outcome, choice.fraction);
}

std::string GestureModel::releaseFlap()
{
  if (!flap_)
    return flap_refusal_;
  const auto chosen = clicked() ? std::nullopt : flap_->nearestResolved(flapTarget());
  std::string message;
  if (chosen)
  {
    const auto& [choice, fold] = *chosen;
    const double way = (flap_->outcomes()[choice.outcome].landing - press_).norm();
    if (choice.miss <= kMissedFold * way)
    {
      const auto [request, kind] = flapFold(fold);
      message = refusal(send(FlatFoldCall{ *request, 1.0, true }));
      if (message.empty())
      {
        message = compoundKindName(kind);
        message[0] = static_cast<char>(std::toupper(static_cast<unsigned char>(message[0])));
        message += ".";
      }
      flap_.reset();
      flap_previewed_.reset();
      pick_ = Pick{};
      return message;
    }
  }
  // No fold: the preview shown goes back to the paper as it is.
  if (flap_previewed_)
  {
    const Expected<CompoundFolds::Resolved> shown = flap_->resolve(flap_previewed_->first);
    if (shown)
      send(FlatFoldCall{ *flapFold(*shown).first, 0.0, false });
  }
  flap_.reset();
  flap_previewed_.reset();
  return clicked() ? "Flap mode: drag the flap where it should lie (a click folds nothing)." :
                     "Not folded: no fold along the creases here takes the flap there. Drag it where a squash, "
                     "petal or reverse fold puts it.";
}

}  // namespace virtual_origami::core
