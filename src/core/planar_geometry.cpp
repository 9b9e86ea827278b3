#include "virtual_origami/core/planar_geometry.h"

namespace virtual_origami::core
{
double segmentDistance(const Vec2& a, const Vec2& b, const Vec2& c, const Vec2& d)
{
  const double abc = cross2(b - a, c - a), abd = cross2(b - a, d - a);
  const double cda = cross2(d - c, a - c), cdb = cross2(d - c, b - c);
  if (((abc > 0 && abd < 0) || (abc < 0 && abd > 0)) && ((cda > 0 && cdb < 0) || (cda < 0 && cdb > 0)))
    return 0.0;
  return std::min({ pointSegmentDistance(a, c, d), pointSegmentDistance(b, c, d), pointSegmentDistance(c, a, b),
                    pointSegmentDistance(d, a, b) });
}

double boundingDiagonal(const std::vector<Vec2>& points)
{
  Vec2 low = points.front(), high = points.front();
  for (const Vec2& p : points)
  {
    low = low.cwiseMin(p);
    high = high.cwiseMax(p);
  }
  return (high - low).norm();
}

}  // namespace virtual_origami::core
