// What the gesture model shows, as plain values, and where its requests and drawings go: the
// interaction node turns them into markers and service calls, a test records them.
#pragma once

#include <optional>
#include <string>
#include <utility>
#include <variant>
#include <vector>

#include "virtual_origami/core/chosen_creases.h"
#include "virtual_origami/core/drag.h"
#include "virtual_origami/core/gesture_requests.h"
#include "virtual_origami/core/view_camera.h"

namespace virtual_origami::core
{
/// The drag's guides: the line being drawn with its snaps, or the ring a face turns on; with
/// neither, the guides are cleared (a crease named as the axis stays shown).
struct Guides
{
  std::optional<CreaseDrag> line;
  std::optional<RotationRing> ring;
  double angle = 0.0;
  std::optional<std::pair<Vec3, Vec3>> named_axis;
};

/// The marks, the face that stays and the picked layer.
struct Picks
{
  std::vector<std::pair<int, CreaseMark>> marks;
  int picked_edge = -1, keep_face = -1, face = -1, vertex = -1;
};

/// Something to tell the user: at `at`, beside the paper (what a click picked: a text over the
/// paper would take the next click) or at the slider's handle. An empty text: what was said no
/// longer applies.
struct Message
{
  enum class Place
  {
    At,
    Beside,
    Slider,
  };
  std::string text;
  Vec3 at = Vec3::Zero();
  Place place = Place::At;
};

/// The seed's view turn for the ring just pressed (to), or back to the view before it (none).
struct ViewTurn
{
  std::optional<ViewCamera> to;
};

/// The curved model holds `vertex` at `target`; vertex -1: it lets go and the bent sheet goes.
struct CurvedHold
{
  int vertex = -1;
  Vec3 target = Vec3::Zero();
};

/// The sheet marker and the menu's check marks are sent again (never during a drag: that would
/// end it in rviz).
struct SheetShown
{};
/// A drag on the sheet ended: the marker goes back under the sheet; `reshow`: and is sent again.
struct SheetReleased
{
  bool reshow = false;
};
/// The fold slider is sent again, its handle at `GestureModel::sliderFraction()` (or taken away
/// from a paper without driven creases).
struct SliderShown
{};
/// The slider's handle and percent moved to `fraction`.
struct SliderMoved
{
  double fraction = 0.0;
};

using GestureOutput =
    std::variant<Guides, Picks, Message, ViewTurn, CurvedHold, SheetShown, SheetReleased, SliderShown, SliderMoved>;

/// Where the model's requests and drawings go: the interaction node's services and markers, or
/// a test's record.
class GestureOutputs
{
public:
  virtual ~GestureOutputs() = default;
  virtual PaperReply send(const PaperRequest& request) = 0;
  virtual void show(const GestureOutput& output) = 0;
};

}  // namespace virtual_origami::core
