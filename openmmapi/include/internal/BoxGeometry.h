#ifndef GENDPDE_BOX_GEOMETRY_H_
#define GENDPDE_BOX_GEOMETRY_H_

/* Geometry of an OpenMM periodic box in reduced form: a = (ax,0,0), b = (bx,by,0), c = (cx,cy,cz). */

#include "openmm/Vec3.h"
#include <algorithm>
#include <cmath>

namespace GenDPDEPlugin {
namespace BoxGeometry {

/** The distances between opposite faces of the box, along each lattice direction (nm). */
inline OpenMM::Vec3 perpendicularWidths(const OpenMM::Vec3 box[3]) {
    double volume = box[0][0]*box[1][1]*box[2][2];
    OpenMM::Vec3 widths;
    for (int k = 0; k < 3; k++) {
        OpenMM::Vec3 normal = box[(k+1)%3].cross(box[(k+2)%3]);
        widths[k] = volume/std::sqrt(normal.dot(normal));
    }
    return widths;
}

/**
 * Half the smallest perpendicular width: the largest range for which no two periodic images of a pair of
 * particles can both be in range. For a rectangular box, half the smallest edge.
 */
inline double halfSmallestWidth(const OpenMM::Vec3 box[3]) {
    OpenMM::Vec3 widths = perpendicularWidths(box);
    return 0.5*std::min(widths[0], std::min(widths[1], widths[2]));
}

/** Fractional coordinates s with r = s0 a + s1 b + s2 c (not wrapped). */
inline OpenMM::Vec3 fractionalCoordinates(const OpenMM::Vec3& r, const OpenMM::Vec3 box[3]) {
    OpenMM::Vec3 s;
    s[2] = r[2]/box[2][2];
    s[1] = (r[1] - s[2]*box[2][1])/box[1][1];
    s[0] = (r[0] - s[2]*box[2][0] - s[1]*box[1][0])/box[0][0];
    return s;
}

} // namespace BoxGeometry
} // namespace GenDPDEPlugin

#endif /*GENDPDE_BOX_GEOMETRY_H_*/
