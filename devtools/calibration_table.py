#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
# Copyright (c) 2026 The openmm-gendpde developers
"""The table of docs/fluids.md "The calibrated fluids" from calibrate's --json records, side by side:

    .venv/bin/python devtools/calibration_table.py docs/figures/calibrated-{water,argon,nitrogen}.json

For each fluid the target, the first measurement ("as mapped": the row of the mapped parameter where calibrate
reports one) and the calibrated model's (value +- standard error (model/target); the pressure as (P - P0) kappa_T,
the quantity it is judged by), then the runs, the wall time and the misses. (The parameters, calibrated/mapped in
OpenMM units, are in calibrate's printed output; the records hold them in reduced units, whose energy unit follows
B_T.)
"""

import argparse
import json
import math
import pathlib

#: (row of the table, the record's row as calibrated, the record's row as mapped or None)
ROWS = [
    ("density n-bar (nm^-3)", "density n-bar (nm^-3)", None),
    ("pressure (MPa)", "pressure, pi0 tuned (MPa)", "pressure, pi0 as mapped (MPa)"),
    ("bulk modulus n dP/dn (MPa)", "bulk modulus n dP/dn (MPa)", "bulk modulus n dP/dn, B_T as mapped (MPa)"),
    ("particle-density response (n/n-bar) dn-bar/dn", "particle-density response (n/n-bar) dn-bar/dn", None),
    ("isochoric heat capacity c_v (J/(kg K))", "isochoric heat capacity c_v (J/(kg K))",
     "isochoric heat capacity c_v, C_V as mapped (J/(kg K))"),
    ("kinetic temperature (K)", "kinetic temperature (K)", None),
    ("harmonic mean of theta_i (K)", "harmonic mean of theta_i (K)", None),
    ("shear viscosity, wave (mPa s)", "shear viscosity, wave (mPa s)",
     "shear viscosity, wave, friction as mapped (mPa s)"),
    ("shear viscosity, Poiseuille flow (mPa s)", "shear viscosity, Poiseuille flow (mPa s)", None),
    ("thermal conductivity, wave (W/(m K))", "thermal conductivity, wave (W/(m K))",
     "thermal conductivity, wave, kappa as mapped (W/(m K))"),
    ("thermal conductivity, heat flux (W/(m K))", "thermal conductivity, heat flux (W/(m K))", None),
    ("not fitted: self-diffusion (1e-9 m^2/s)", "not fitted: self-diffusion (1e-9 m^2/s)", None),
    ("not fitted: speed of sound (m/s)", "not fitted: speed of sound, from n dP/dn, (dP/dT)_n and c_v (m/s)", None),
    ("measured: speed of sound, sound wave (m/s)", "measured: speed of sound, sound wave (m/s)", None),
]
#: Rows that records written before issue 54 name otherwise (the speed of sound then took the kinetic (dP/dT)_n).
EARLIER_ROWS = {"not fitted: speed of sound, from n dP/dn, (dP/dT)_n and c_v (m/s)":
                "not fitted: speed of sound, from n dP/dn (m/s)"}


def _missed(record):
    """The properties a record missed: its "missed_properties" (calibrate writes them), or for a record written before
    it did, the row of each "missed" line."""
    return record.get("missed_properties", [line.split(":")[0] for line in record["missed"]])


def _cell(entry, compressibility, pressure):
    if entry is None:
        return ""
    value, error, target = entry["model"], entry["error"], entry["target"]
    if value is None or (isinstance(value, float) and math.isnan(value)):
        return "-"
    text = f"{value:.4g} +- {error:.2g}"
    if pressure:
        return text + f" ((P - P0) kappa_T {(value - target) * compressibility:+.4f})"
    if target and not math.isnan(target):
        return text + f" ({value / target:.3f})"
    return text


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("records", nargs="+", type=pathlib.Path)
    arguments = parser.parse_args()
    records = [json.loads(path.read_text()) for path in arguments.records]
    names = [record["fluid"].split(",")[0].split(" (")[0].replace("liquid ", "") for record in records]
    header = ["property"] + [f"{name} {column}" for name in names for column in ("target", "as mapped", "calibrated")]
    print("| " + " | ".join(header) + " |")
    print("|" + "---|" * len(header))
    for label, calibrated, mapped in ROWS:
        cells = [label]
        for record in records:
            results = record["results"]
            row = calibrated if calibrated in results else EARLIER_ROWS.get(calibrated, calibrated)
            if row not in results:
                cells += ["", "", ""]
                continue
            # (P - P0) kappa_T: the bulk modulus target is 1/kappa_T (MPa)
            compressibility = 1 / results["bulk modulus n dP/dn (MPa)"]["target"]
            pressure = label.startswith("pressure")
            target = results[row]["target"]
            cells.append("-" if target is None or math.isnan(target) else f"{target:.4g}")
            cells.append(_cell(results.get(mapped) if mapped else None, compressibility, pressure))
            cells.append(_cell(results[row], compressibility, pressure))
        print("| " + " | ".join(cells) + " |")
    print()
    for name, record in zip(names, records):
        print(f"- {name}: {record['runs']} runs in {record['wall_time_s'] / 60:.1f} min; "
              f"missed: {'; '.join(_missed(record)) or 'nothing'}")


if __name__ == "__main__":
    main()
