#!/usr/bin/env python3
"""The building's baked light carried past the last sunny slot, read on the lightmap itself (issue 44 item 4).

A bake set of the same site with three sunny slots to carry from (09:00, 12:00, 15:00), the instants to carry to
(16:30, 06:30) and the sunny sky with the sun below the horizon (21:00: each texel's sky part S alone) gives, per
texel, the truth of each model of the carry without the camera or a path tracer's noise:

  held              E of the nearest slot
  mean carry        the runtime's (gusuku/maths/indirect_carry.h): one factor, the building's mean S + B g fitted
  sin h, S fitted   each texel's own S (least squares over the slots, per channel) and its bounce times
                    g_now / g_slot, g = E_sun sin h
  sin h, S baked    the same with the baked S
  E_sun, S baked    the bounce times E_sun,now / E_sun,slot (a sun-facing wall's)

Printed: each model's luminance summed over the texels over the bake's, for all valid texels and for those lit
mostly by the sky (S / E > 0.6 at the slot: roofs) or by the sun's bounce (S / E < 0.4: walls under eaves).
Bake the folder with a site.json whose bake.slots are those six (docs/site-json.md), e.g.
  gusuku-bake bake site.json -o BAKESET --quiet
Usage: carry_past_slots.py BAKESET   (needs numpy and the OpenEXR module)
"""
import json
import sys

import numpy as np
import OpenEXR

LUMINANCE = np.array([0.2126, 0.7152, 0.0722])
FIT_SLOTS = ('sunny_0900', 'sunny_1200', 'sunny_1500')
CARRIES = (('sunny_1630', 'sunny_1500'), ('sunny_0630', 'sunny_0900'))  # (to, from the nearest slot)
SKY_ONLY = 'sunny_2100'


def main(folder):
    slots = {slot['name']: slot for slot in json.load(open(f'{folder}/manifest.json'))['slots']}

    def image(name):
        with OpenEXR.File(f'{folder}/building_{name}.exr') as exr:
            channels = exr.channels()
            rgba = channels['RGBA'].pixels if 'RGBA' in channels else np.stack([channels[c].pixels for c in 'RGBA'], -1)
            return np.asarray(rgba, np.float64)

    def sun(name):
        return np.array(slots[name]['sun']['irradiance_rgb'])

    def sin_h(name):
        return np.sin(np.radians(slots[name]['sun']['apparent_elevation_deg']))

    lit = np.stack([image(name)[..., :3] for name in FIT_SLOTS])
    valid = image(FIT_SLOTS[0])[..., 3] > 0
    g = np.stack([sun(name) * sin_h(name) for name in FIT_SLOTS])
    mean_g, variance_g = g.mean(0), ((g - g.mean(0)) ** 2).mean(0)
    per_sun = np.einsum('kc,khwc->hwc', (g - mean_g) / (len(FIT_SLOTS) * variance_g), lit)
    sky_fitted = np.maximum(lit.mean(0) - np.maximum(per_sun, 0) * mean_g, 0)
    sky_baked = image(SKY_ONLY)[..., :3]
    # The building's mean fit in luminance, as indirect_carry.cpp makes it.
    g_y = g @ LUMINANCE
    mean_y = np.array([(slot[valid] @ LUMINANCE).mean() for slot in lit])
    b_mean = max(np.cov(g_y, mean_y, bias=True)[0, 1] / g_y.var(), 0.0)
    s_mean = mean_y.mean() - b_mean * g_y.mean()

    for target, slot in CARRIES:
        held, truth = image(slot)[..., :3], image(target)[..., :3]
        g_ratio = sun(target) * sin_h(target) / (sun(slot) * sin_h(slot))
        g_now, g_slot = sun(target) * sin_h(target) @ LUMINANCE, sun(slot) * sin_h(slot) @ LUMINANCE
        models = {
            'held': held,
            'mean carry': held * (s_mean + b_mean * g_now) / (s_mean + b_mean * g_slot),
            'sin h, S fitted': sky_fitted + (held - sky_fitted) * g_ratio,
            'sin h, S baked': sky_baked + (held - sky_baked) * g_ratio,
            'E_sun, S baked': sky_baked + (held - sky_baked) * sun(target) / sun(slot),
        }
        sky_share = (sky_baked @ LUMINANCE) / np.maximum(held @ LUMINANCE, 1e-9)
        groups = {'all': valid, 'sky-lit': valid & (sky_share > 0.6), 'bounce-lit': valid & (sky_share < 0.4)}
        print(f'{target} from {slot}: ' + ', '.join(f'{name} {mask.sum()} texels' for name, mask in groups.items()))
        for model, predicted in models.items():
            ratios = [(predicted[mask] @ LUMINANCE).sum() / (truth[mask] @ LUMINANCE).sum() for mask in groups.values()]
            print(f'  {model:16s} ' + ' '.join(f'{name} {ratio:.3f}' for name, ratio in zip(groups, ratios)))


if __name__ == '__main__':
    if len(sys.argv) != 2:
        sys.exit(__doc__.strip().splitlines()[-1])
    main(sys.argv[1])
