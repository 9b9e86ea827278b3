// ORIPA crease patterns (https://github.com/oripa/oripa): `.cp` text and `.opx` XML, read into a
// flat Paper. Both formats hold bare line segments; the reader builds the planar graph they draw.
#pragma once

#include <string>
#include <vector>

#include "virtual_origami/core/paper.h"
#include "virtual_origami/core/result.h"

namespace virtual_origami::core
{
/// One line of a crease pattern, in the file's own frame. ORIPA's line types: 1 cut (the
/// paper's outline: Boundary), 2 Mountain, 3 Valley; 0 and 4 are auxiliary lines (drawing aids,
/// no crease: ORIPA's own .cp reader treats 4 so), which the parsers leave out.
struct CreaseSegment
{
  Vec2 a = Vec2::Zero();
  Vec2 b = Vec2::Zero();
  Assignment assignment = Assignment::Boundary;
  int line = 0;  // 1-based line of the file it came from, for messages
};

/// `.cp`: one segment a line, `type x1 y1 x2 y2`, separated by spaces or tabs; blank lines are
/// skipped. Refuses, naming the line, a line without exactly five fields, a type that is not one
/// of 0–4, or a coordinate that is not a finite number. Messages never quote the file.
Expected<std::vector<CreaseSegment>> parseOripaCpSegments(const std::string& text);

/// `.opx`: ORIPA's java.beans.XMLEncoder document; every `<object class="oripa.OriLineProxy">`
/// is a segment, its properties x0, y0, x1, y1 (double) and type (int) each 0 when absent, as
/// XMLEncoder leaves out defaults. Other content (title, author, memo) is ignored. Refuses,
/// naming the line, broken XML around the lines, and values as parseOripaCpSegments does.
Expected<std::vector<CreaseSegment>> parseOripaOpxSegments(const std::string& text);

/// The paper the segments draw. The outline's (Boundary segments') bounding box is scaled,
/// keeping its proportions, so its longer side spans [0, `size`] with the corner at the origin;
/// y keeps its direction (as ORIPA's own FOLD export). Segments are split at every crossing and
/// T-junction, points within 1e-8·size merged, collinear runs of one kind through a vertex of
/// degree 2 joined, and the faces traced counter-clockwise. Edges on the outline are Boundary
/// (whatever the line's type), inner edges keep M/V; the paper is flat (folded = crease pattern
/// in z = 0, fold angles 0). Refuses, naming a line: no Boundary segment, a zero-length segment,
/// one outside the outline's box, a line ending inside a face, a part not joined to the rest, a
/// cut line inside the paper (slits are not modelled), mountain and valley on the same stretch,
/// and a face that is not convex.
Expected<Paper> paperFromSegments(const std::vector<CreaseSegment>& segments, double size = 1.0);

/// parseOripa*Segments then paperFromSegments.
Expected<Paper> parseOripaCp(const std::string& text, double size = 1.0);
Expected<Paper> parseOripaOpx(const std::string& text, double size = 1.0);

/// Reads a `.cp` or `.opx` file, chosen by its extension (case-insensitive). Messages start with
/// the path.
Expected<Paper> readCreasePatternFile(const std::string& path, double size = 1.0);

}  // namespace virtual_origami::core
