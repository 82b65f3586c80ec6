import sys, time
import numpy as np
from softpad.box import open_box
from softpad.layout import PadLayout
from softpad.planning import NoiseDetectionParams, NoiseObjectDetector
t0 = time.process_time()
alpha = float(sys.argv[1]); n = int(sys.argv[2]); wait = float(sys.argv[3]); extra = sys.argv[4] if len(sys.argv) > 4 else ""
lay = PadLayout()
fa = 0; zs = []
for seed in range(1000, 1000 + n):
    with open_box(f"sim://?inflated_kpa=1.1&seed={seed}{extra}") as box:
        ref = np.array([f.pressures_pa[:6] for f in box.read_many(10)])
        det = NoiseObjectDetector(NoiseDetectionParams(false_alarm=alpha)); det.calibrate(ref)
        box.read_many(int(wait * box.sample_rate_hz))
        judged = np.array([f.pressures_pa[:6] for f in box.read_many(10)]).mean(0) - ref.mean(0)
        fa += bool(det.objects(judged, lay))
        zs.append(judged / det.params.increment_std_pa(det.spread_pa))
zs = np.array(zs)
print("alarms", fa, "of", n, "z std", zs.std(), "thr", det.threshold_pa(6), "cpu", time.process_time() - t0)
