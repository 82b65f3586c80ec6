"""Phantom objects on an idle pad: the loop's ObjectWatch + planning decision with the
noise detector, on the compare command's idle box (disturbances on), per simulated hour."""
import sys, time
import numpy as np
from softpad.box import open_box
from softpad.control import ObjectWatch
from softpad.layout import PadLayout
from softpad.planning import NoiseObjectDetector
from softpad.sensing import ThesisObjectDetector, measured_change
hours = float(sys.argv[1]); seed = int(sys.argv[2]); rate = float(sys.argv[3]) if len(sys.argv) > 3 else 100.0; dist = sys.argv[4] if len(sys.argv) > 4 else "1"
lay = PadLayout(); t0 = time.process_time()
url = f"sim://?rate_hz={rate:g}&inflated_kpa=1.1&disturbances={dist}&seed={seed}"
with open_box(url) as box:
    ref_reads = np.array([f.pressures_pa[:6] for f in box.read_many(10)])
    ref = ref_reads.mean(0)
    det = NoiseObjectDetector(); det.calibrate(ref_reads)
    thesis = ThesisObjectDetector()
    counts = {"seen": 0, "settled": 0, "planned": 0, "thesis_seen": 0}
    n = int(hours * 3600 * rate)
    w = ObjectWatch(ref, det, lay, 10, 1.0); wt = ObjectWatch(ref, thesis, lay, 10, 1.0)
    done = 0; maxinc = -1e9
    while done < n:
        block = np.array([f.pressures_pa[:6] for f in box.read_many(min(20000, n - done))])
        ts = box.time_s - (len(block) - 1 - np.arange(len(block))) / rate
        i = 0
        while i < len(block):
            s = w.update(block[i], ts[i]); st = wt.update(block[i], ts[i])
            if st == "seen": counts["thesis_seen"] += 1
            if s == "seen": counts["seen"] += 1
            if s == "settled":
                counts["settled"] += 1
                plan = block[i + 1:i + 11]
                if len(plan) == 10 and det.objects(measured_change(plan.mean(0) - ref), lay):
                    counts["planned"] += 1
                w = ObjectWatch(ref, det, lay, 10, 1.0)
            i += 1
        maxinc = max(maxinc, float((block - ref).max()))
        done += len(block)
print(dict(hours=hours, seed=seed, rate=rate, disturbances=dist, thr=round(det.threshold_pa(6), 2), spread=round(det.spread_pa, 2), max_raw_inc=round(maxinc, 1), **counts, cpu=round(time.process_time() - t0, 1)))
