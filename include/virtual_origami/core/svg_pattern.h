// Crease patterns drawn as SVG in Origami Simulator's convention (its own example library and
// the files people draw for it): every stroked line is an edge, its colour the kind, its opacity
// how far it folds. (core/svg.h is the other way: the paper drawn as SVG.)
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "virtual_origami/core/paper.h"
#include "virtual_origami/core/result.h"

namespace virtual_origami::core
{
/// One straight stroke of the drawing, in the SVG's user space after every transform (y down).
struct SvgStroke
{
  Vec2 a = Vec2::Zero();
  Vec2 b = Vec2::Zero();
  Assignment assignment = Assignment::Boundary;
  /// Mountains and valleys: opacity × stroke-opacity of 180°, negative for a mountain.
  std::optional<double> target_angle;
  std::string element;  // "<path> on line 12", for messages
};

/// The strokes an SVG draws: `<line>`, `<polyline>`, `<polygon>`, `<rect>`, `<circle>`,
/// `<ellipse>` and `<path>` (every command, absolute and relative; curves and arcs as polylines),
/// each through the `transform`s of its groups and its own (matrix, translate, scale, rotate,
/// skewX, skewY). The stroke colour, from the element's `style`, a `<style>` sheet rule for its
/// tag or class, its `stroke` attribute, or its groups', is the kind: black #000 border (B), red
/// #f00 mountain (M), blue #00f valley (V), green #0f0 cut (C), yellow #ff0 facet held flat (F),
/// magenta #f0f undriven hinge (U). Elements with no stroke (or `none`), and those inside
/// `<defs>`, `<symbol>`, `<clipPath>`, `<mask>`, `<marker>`, `<pattern>` or hidden by
/// `display: none`, draw nothing. Refuses, naming the element and its line, a stroke of any other
/// colour and malformed geometry; and broken XML, naming the line. Messages never quote the file.
Expected<std::vector<SvgStroke>> parseSvgStrokes(const std::string& text);

/// The paper an SVG crease pattern draws. As ORIPA's: the border's bounding box (the drawing's,
/// without border strokes) scaled so its longer side is `size`, corner at the origin, y turned up
/// so the pattern looks as it does drawn; points closer than Origami Simulator's merge tolerance
/// (3 user units, or 1% of the box where that is smaller) are one; strokes split where they cross
/// or meet; the faces traced as for a FOLD file without faces (tracePaper: holes, cuts opened,
/// several pieces), concave faces split into convex pieces. Where strokes of several kinds land
/// on one stretch (drawn over each other, or brought together by the merge tolerance), it keeps
/// the first of border, mountain, valley, cut, facet, hinge, as Origami Simulator does.
Expected<Paper> parseSvgPattern(const std::string& text, double size = 1.0);

}  // namespace virtual_origami::core
