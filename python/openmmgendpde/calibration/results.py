# SPDX-License-Identifier: MIT
# Copyright (c) 2026 The openmm-gendpde developers
"""What calibrate judges: each property as a typed value (Property), the criteria it must meet (CRITERIA, and those
of --quick), and the misses, each naming its property. The labels of the report are attributes of the properties:
renaming one changes no judgement."""

import dataclasses
import enum
import re


class Property(enum.Enum):
    """A property that calibrate measures and judges: (its row in the report, with the unit; the quantity it
    measures, as an iteration that sets it names it). Two methods of one quantity are two properties (the shear
    viscosity by the wave and by the Poiseuille flow)."""
    DENSITY = ("density n-bar (nm^-3)", "density n-bar")
    PRESSURE = ("pressure, pi0 tuned (MPa)", "pressure")
    BULK_MODULUS = ("bulk modulus n dP/dn (MPa)", "bulk modulus n dP/dn")
    HEAT_CAPACITY = ("isochoric heat capacity c_v (J/(kg K))", "isochoric heat capacity c_v")
    KINETIC_TEMPERATURE = ("kinetic temperature (K)", "kinetic temperature")
    HARMONIC_TEMPERATURE = ("harmonic mean of theta_i (K)", "harmonic mean of theta_i")
    VISCOSITY_WAVE = ("shear viscosity, wave (mPa s)", "shear viscosity")
    VISCOSITY_FLOW = ("shear viscosity, Poiseuille flow (mPa s)", "shear viscosity")
    CONDUCTIVITY_WAVE = ("thermal conductivity, wave (W/(m K))", "thermal conductivity")
    CONDUCTIVITY_HEAT_FLUX = ("thermal conductivity, heat flux (W/(m K))", "thermal conductivity")
    THERMAL_EXPANSION = ("thermal expansion alpha, beta corrected (1e-3/K)", "thermal expansion alpha")

    @property
    def label(self):
        """The row of the report (the unit in parentheses)."""
        return self.value[0]

    @property
    def quantity(self):
        return self.value[1]

    @property
    def name_in_report(self):
        """The row without its unit: "shear viscosity, wave"."""
        return re.sub(r" \(.*\)$", "", self.label)

    @property
    def transport(self):
        return self.quantity in ("shear viscosity", "thermal conductivity")


@dataclasses.dataclass
class Measured:
    """A measured value and its standard error; ``samples``: the independent samples the error rests on (N/g of
    a time series, or the replicas), None where it is derived from other measurements."""
    value: float
    error: float
    samples: float = None


@dataclasses.dataclass(frozen=True)
class Criterion:
    """What a property must reach. ``kind`` 'relative': |model/target - 1| <= tolerance; 'pressure': |P - P0| <=
    tolerance times the bulk modulus 1/kappa_T (P0 may be ~0); 'factor': model/target within [1/tolerance,
    tolerance]. Each range is widened by the model's 95% interval (coverage: 2 standard errors, or Student's t for
    the few replicas of a transport coefficient)."""
    kind: str
    tolerance: float


#: What a calibration must reach, by property (one it has not measured, such as the thermal expansion of a fluid
#: without one, is not judged). The transport coefficients are iterated (gamma, kappa) on the wave decays to 5% and
#: measured again by the steady flows of transport.py, which must reach the same 5%. The thermal expansion's beta is
#: iterated (thermal_expansion_rows) and must reach 5%.
CRITERIA = {
    Property.DENSITY: Criterion("relative", 0.02),
    Property.PRESSURE: Criterion("pressure", 0.01),
    Property.BULK_MODULUS: Criterion("relative", 0.05),
    Property.HEAT_CAPACITY: Criterion("relative", 0.02),
    Property.KINETIC_TEMPERATURE: Criterion("relative", 0.02),
    Property.HARMONIC_TEMPERATURE: Criterion("relative", 0.02),
    Property.VISCOSITY_WAVE: Criterion("relative", 0.05),
    Property.VISCOSITY_FLOW: Criterion("relative", 0.05),
    Property.CONDUCTIVITY_WAVE: Criterion("relative", 0.05),
    Property.CONDUCTIVITY_HEAT_FLUX: Criterion("relative", 0.05),
    Property.THERMAL_EXPANSION: Criterion("relative", 0.05),
}
#: What --quick is judged on: CRITERIA, but each transport coefficient within a factor 2, and not the bulk modulus.
#: Its boxes are too small for 5%: in a cube of 500 particles the transverse wave (k = 2 pi/L, L ~ 4.7 R for water)
#: reads the viscosity ~0.7 of what it reads in 2048 particles, where it agrees with the Poiseuille flow; its two
#: B_T runs are a functional check of the iteration (docs/fluids.md).
QUICK_CRITERIA = {prop: Criterion("factor", 2.0) if prop.transport else criterion
                  for prop, criterion in CRITERIA.items() if prop is not Property.BULK_MODULUS}


@dataclasses.dataclass(frozen=True)
class Miss:
    """A result that missed its criterion (``property`` set), or an iteration that could not reach its target (the
    quantity it sets: ``quantity``); ``text`` says by how much, or why. str() is the text."""
    quantity: str
    text: str
    property: Property = None

    def __str__(self):
        return self.text

    @classmethod
    def of_iteration(cls, prop, text):
        """The failure ``text`` of the iteration that sets the quantity of ``prop`` (None: no failure, no Miss)."""
        return [] if text is None else [cls(prop.quantity, str(text))]


#: The report's rows that are not judged but compared as pressures, (P - P0) kappa_T.
PRESSURE_ROWS = ("pressure, pi0 as mapped (MPa)",)


def comparison(prop, target, model, bulk_modulus):
    """How ``model`` compares with ``target`` for ``prop`` (a Property, or a row of the report that is not judged):
    (P - P0) kappa_T for a pressure (P0 may be ~0), else model/target."""
    if prop is Property.PRESSURE or prop in PRESSURE_ROWS:
        return f"(P - P0) kappa_T = {(model - target) / bulk_modulus:.4f}"
    return f"model/target = {model / target:.3f}"


def misses(results, criteria=CRITERIA):
    """A Miss for each property of ``criteria`` (CRITERIA or QUICK_CRITERIA) whose result missed it, saying by how
    much; ``results``: Property -> {target, model, error, samples (optional)}, the pressures in the unit of the bulk
    modulus's target."""
    bulk_modulus = results[Property.BULK_MODULUS]["target"]
    found = []
    for prop, criterion in criteria.items():
        if prop not in results:
            continue
        target, model, error = (results[prop][key] for key in ("target", "model", "error"))
        if criterion.kind == "factor":
            low, high = target / criterion.tolerance, target * criterion.tolerance
        else:
            width = criterion.tolerance * (bulk_modulus if criterion.kind == "pressure" else abs(target))
            low, high = target - width, target + width
        factor = coverage(results[prop].get("samples"))
        if not low - factor * error <= model <= high + factor * error:
            found.append(Miss(prop.quantity, f"{prop.label}: {model:.5g} +- {error:.2g} against the target "
                                             f"{target:.5g} ({comparison(prop, target, model, bulk_modulus)}); allowed "
                                             f"{low:.5g} to {high:.5g}, widened by {factor:.3g} standard errors", prop))
    return found


def missed_properties(found):
    """The names of what ``found`` (Misses) missed, each once, in order: a property by its row ("shear viscosity,
    wave"), an iteration's failure by its quantity, unless a property of that quantity missed too (the bulk
    modulus's row and its iteration's advice are one property, not two)."""
    judged = {miss.quantity for miss in found if miss.property is not None}
    names = [miss.property.name_in_report if miss.property is not None else miss.quantity for miss in found
             if miss.property is not None or miss.quantity not in judged]
    return list(dict.fromkeys(names))


def coverage(samples):
    """How many standard errors a 95% interval spans when the error rests on ``samples`` independent samples (the
    replicas, or N/g of a time series): Student's t quantile t(0.975, samples - 1), at least 2 (2 when not known).
    A standard error from 4 replicas is itself uncertain by ~40%; t(0.975, 3) = 3.18 says so: argon's conductivity
    wave read 0.107 +- 0.0044 W/(m K) in one set of 4 replicas and 0.127 +- 0.017, 0.106 +- 0.015 in two more at the
    same parameters (docs/fluids.md)."""
    if samples is None or not samples > 1:
        return 2.0
    from scipy.stats import t
    return max(2.0, float(t.ppf(0.975, samples - 1)))
