"""Share of placements over the 2x3 pad at which a light object's largest module increment
exceeds a threshold (project FEM: PadResponse cast pad at p0, sealed rise), by mass."""
import numpy as np
from softpad.sim import PadResponse
r = PadResponse(); lay = r.layout; P = lay.pitch_m; g = 9.81
def max_rise_per_g(size):
    xs = np.linspace(0.5 * size[0], 3 * P - 0.5 * size[0], 55)
    ys = np.linspace(0.5 * size[1], 2 * P - 0.5 * size[1], 37)
    out = []
    for y in ys:
        for x in xs:
            eq = r.rect_equivalent_loads((x, y), size, g * 1e-3, 1100.0)
            out.append(r.sealed_rise_pa(eq, 1100.0).max())
    return np.array(out)
for label, size in (("16 mm cube (die)", (0.016, 0.016)), ("8 mm contact (ball, fruit)", (0.008, 0.008)),
                    ("60 x 90 mm face (sponge)", (0.06, 0.09)), ("12 x 130 mm strip (marker)", (0.012, 0.13))):
    m = max_rise_per_g(size)
    print(f"{label}: Pa/g largest module: median {np.median(m):.2f}, max {m.max():.2f}")
    for thr in (50.0, 44.0, 21.9, 11.0):
        row = []
        for mass in (5, 6, 10, 15, 20, 25):
            row.append(f"{mass} g {100 * np.mean(m * mass > thr):3.0f}%")
        print(f"  t = {thr:5.1f} Pa:", ", ".join(row))
