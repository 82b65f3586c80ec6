"""Design a pad for your own objects: three designs (plus the thesis's pad) on the packaged
'blocks' set (a 12.6 g brick, a 250 g block, a can lying down), in this process's local Dask
cluster, nothing cached. Prints the ranked table."""

from __future__ import annotations

from softpad.design import (
    PadDesign,
    ResultCache,
    TrialOptions,
    design_sweep,
    example_object_set,
)


def main() -> dict:
    objects = example_object_set("blocks")
    designs = [
        PadDesign(3, 3, 0.035),  # a finer, nearly square pad
        PadDesign(thickness_m=0.001),  # the thesis's grid with a thinner layer
        PadDesign(p0_pa=2000.0),  # the thesis's pad inflated higher
    ]
    result = design_sweep(
        designs,
        objects,
        TrialOptions(hold_s=1.0),
        seeds=(0,),
        quick=True,
        workers=1,
        cache=ResultCache(None),
    )
    print(result.to_text())
    return result.to_dict()


if __name__ == "__main__":
    main()
