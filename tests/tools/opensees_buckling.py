#!/usr/bin/env python3
"""The critical load factor of a lamella OpenSees export, found by OpenSees.

Usage: python3 opensees_buckling.py SCRIPT.py

Imports the exported script, builds its model with P-Delta transformations
and applies its first load set times lambda in one Newton step; the
tangent stiffness there is positive definite (its smallest eigenvalue with
unit nodal masses, -fullGenLapack, is positive) below the critical factor
and not beyond it. Doubling brackets it, bisection narrows it to 1e-5
(relative). Prints {"alpha_cr": ...} as JSON.
"""
import importlib.util
import json
import sys

import openseespy.opensees as ops


def stable(model, lam):
    model.build('PDelta')
    model.LOAD_SETS[0]()
    ops.constraints('Plain')
    ops.numberer('RCM')
    ops.system('BandGeneral')
    ops.test('NormDispIncr', 1e-9, 30)
    ops.algorithm('Newton')
    ops.integrator('LoadControl', lam)
    ops.analysis('Static')
    if ops.analyze(1) != 0:
        return False
    # The sign of the tangent's smallest eigenvalue (unit masses: the
    # signs are those of K_T's eigenvalues).
    for tag in ops.getNodeTags():
        ops.mass(tag, 1.0, 1.0, 1.0, 1.0, 1.0, 1.0)
    return ops.eigen('-fullGenLapack', 1)[0] > 0.0


def main():
    if len(sys.argv) != 2:
        sys.exit('usage: python3 opensees_buckling.py SCRIPT.py')
    spec = importlib.util.spec_from_file_location('exported', sys.argv[1])
    model = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(model)
    ops.logFile('/dev/null', '-noEcho')
    lo, hi = 0.0, 1.0
    while stable(model, hi):
        lo, hi = hi, 2.0 * hi
        if hi > 1e12:
            sys.exit('no critical factor below 1e12')
    while hi - lo > 1e-5 * hi:
        mid = 0.5 * (lo + hi)
        if stable(model, mid):
            lo = mid
        else:
            hi = mid
    print(json.dumps({'alpha_cr': 0.5 * (lo + hi)}))


if __name__ == '__main__':
    main()
