/* SPDX-License-Identifier: MIT
 * Copyright (c) 2026 The openmm-gendpde developers */
#ifndef GENDPDE_BOX_GEOMETRY_H_
#define GENDPDE_BOX_GEOMETRY_H_

/* Geometry of an OpenMM periodic box in reduced form: a = (ax,0,0), b = (bx,by,0), c = (cx,cy,cz). */

#include "openmm/OpenMMException.h"
#include "openmm/Vec3.h"
#include <algorithm>
#include <cmath>
#include "gendpde/IntegerRounding.h"
#include "internal/MessageText.h"
#include <string>

namespace GenDPDEPlugin {
namespace BoxGeometry {

/** The distances between opposite faces of the box, along each lattice direction (nm). */
inline OpenMM::Vec3 perpendicularWidths(const OpenMM::Vec3 box[3]) {
    double volume = box[0][0] * box[1][1] * box[2][2];
    OpenMM::Vec3 widths;
    for (int k = 0; k < 3; k++) {
        OpenMM::Vec3 normal = box[(k + 1) % 3].cross(box[(k + 2) % 3]);
        widths[k] = volume / std::sqrt(normal.dot(normal));
    }
    return widths;
}

/**
 * Half the smallest perpendicular width: the largest range for which no two periodic images of a pair of
 * particles can both be in range. For a rectangular box, half the smallest edge.
 */
inline double halfSmallestWidth(const OpenMM::Vec3 box[3]) {
    OpenMM::Vec3 widths = perpendicularWidths(box);
    return 0.5 * std::min(widths[0], std::min(widths[1], widths[2]));
}

/**
 * Throw an OpenMMException naming `owner` (the class whose range it is) if a pair range exceeds half the smallest
 * perpendicular width of the periodic box, beyond which two images of a pair could both be in range. Checked at
 * Context creation and before every step or evaluation that uses the range (a barostat may shrink the box).
 */
inline void checkCutoffAgainstBox(const std::string& owner, double cutoff, const OpenMM::Vec3 box[3]) {
    const double limit = halfSmallestWidth(box);
    if (cutoff > limit) {
        MessageText message;
        message.precision(12);
        message << owner << ": cutoff distance = " << cutoff << " nm is not allowed with this periodic box; "
                << "it must be <= half the smallest box width (" << limit << " nm; for a rectangular box the "
                << "width is the edge length, for a triclinic one the distance between opposite faces)";
        throw OpenMM::OpenMMException(message.str());
    }
}

/** Fractional coordinates s with r = s0 a + s1 b + s2 c (not wrapped). */
inline OpenMM::Vec3 fractionalCoordinates(const OpenMM::Vec3& r, const OpenMM::Vec3 box[3]) {
    OpenMM::Vec3 s;
    s[2] = r[2] / box[2][2];
    s[1] = (r[1] - s[2] * box[2][1]) / box[1][1];
    s[0] = (r[0] - s[2] * box[2][0] - s[1] * box[1][0]) / box[0][0];
    return s;
}

} // namespace BoxGeometry
} // namespace GenDPDEPlugin

#endif /*GENDPDE_BOX_GEOMETRY_H_*/
