/* The polynomial branch of the V-B integrals (docs/theory.md section 3) gives the same bits whichever way it is
 * evaluated: the SIMD form used with GCC and Clang and the portable form used with other compilers. (Their accuracy
 * against 40-digit quadrature is tested in python/tests/test_volume_estimators.py.) */

#include "TestUtilities.h"
#include "internal/GenDPDEPhysics.h"
#include <cstring>
#include <stdexcept>
#include <string>

using namespace GenDPDEPlugin::Physics;

void testSimdAndPortableEvaluationAgree() {
    using namespace VolumeVBPolynomials;
    const int numPieces = (lastOctave - firstOctave + 1)*subintervals;
    for (int piece = 0; piece < numPieces; piece++)
        for (int m = 0; m <= 1000; m++) {
            const double t = -1.0 + 2.0*m/1000.0;
            const VolumeIntegralsVB simd = evaluate(coefficients[piece], t);
            const VolumeIntegralsVB portable = evaluatePortable(coefficients[piece], t);
            if (std::memcmp(&simd.I, &portable.I, sizeof(double)) != 0
                    || std::memcmp(&simd.J, &portable.J, sizeof(double)) != 0)
                throw std::runtime_error("piece " + std::to_string(piece) + ", t = " + std::to_string(t)
                                         + ": SIMD and portable evaluations differ");
        }
}

int main() {
    return runTestProgram([]() {
        testSimdAndPortableEvaluationAgree();
    });
}
