#include "virtual_origami/core/obj_export.h"

#include <iomanip>
#include <limits>
#include <sstream>

namespace virtual_origami::core
{
std::string formatObj(const Paper& paper)
{
  std::ostringstream obj;
  obj << std::setprecision(std::numeric_limits<double>::max_digits10);
  obj << "# virtual_origami: " << paper.vertices.size() << " vertices, " << paper.faces.size() << " faces\n";
  const double scale = paper.scale();
  for (const Vertex& v : paper.vertices)
    obj << "v " << v.folded.x() << ' ' << v.folded.y() << ' ' << v.folded.z() << '\n';
  for (const Vertex& v : paper.vertices)  // texture coordinates: where the point lies on the sheet
    obj << "vt " << v.crease_pattern.x() / scale << ' ' << v.crease_pattern.y() / scale << '\n';
  for (const Face& f : paper.faces)
  {
    obj << 'f';
    for (int v : f.vertices)
      obj << ' ' << v + 1 << '/' << v + 1;
    obj << '\n';
  }
  return obj.str();
}

}  // namespace virtual_origami::core
