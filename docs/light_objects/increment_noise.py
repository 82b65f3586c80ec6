"""Empty-pad increment noise after the loop's adjustment (analytic world, sim box)."""
import sys, json, math
import numpy as np
from dataclasses import replace
from softpad.box import SimBox
from softpad.sim import AnalyticWorld, SensorParams
from softpad.control import inflate_and_adjust

def one(seed, scale, rate, wait_s=1.2, watch_s=2.0):
    base = SensorParams()
    sensor = replace(base, noise_std_pa=base.noise_std_pa*scale, drift_std_pa=base.drift_std_pa*scale,
                     offset_std_pa=base.offset_std_pa*scale)
    box = SimBox(AnalyticWorld(), sample_rate_hz=rate, seed=seed, sensor=sensor, initial_pressure_pa=1.0e3)
    frames = []
    marks = {}
    with box:
        adj = inflate_and_adjust(box, 6, on_frame=lambda f: frames.append(f.pressures_pa[:6].copy()),
                                 on_adjusted=lambda t: marks.setdefault("adj", len(frames)))
        refreads = np.array(frames[marks["adj"]:marks["adj"]+10])
        n_watch = int(round(watch_s*rate))
        after = np.array([box.read().pressures_pa[:6] for _ in range(n_watch)])
    ref = adj.reference_pa
    k = int(round(wait_s*rate))
    plan_inc = after[k:k+10].mean(axis=0) - ref
    # watch: running 10-mean
    c = np.cumsum(np.vstack([np.zeros(6), after - ref]), axis=0)
    filt = (c[10:] - c[:-10]) / 10
    s_ref = float(np.sqrt(np.mean(refreads.var(axis=0, ddof=1))))
    d1 = np.diff(refreads, axis=0)
    return dict(seed=seed, scale=scale, rate=rate, plan_inc=plan_inc.tolist(), ref_spread=s_ref,
                watch_max=float(filt.max()), watch_min=float(filt.min()),
                ref_check=float(np.abs(refreads.mean(axis=0)-ref).max()))

if __name__ == "__main__":
    seeds = range(int(sys.argv[1]), int(sys.argv[2]))
    out = []
    for scale in (0.5, 1.0, 2.0):
        for rate in (50.0, 100.0, 200.0):
            for s in seeds:
                try:
                    out.append(one(s, scale, rate))
                except Exception as e:
                    out.append(dict(seed=s, scale=scale, rate=rate, fault=str(e)))
    json.dump(out, sys.stdout)
