#!/usr/bin/env python3
# Makes the still, shifted and blurred images of the cvvdp golden cases (README.md).
# Run from the repository root: python3 tests/data/cvvdp/make_pngs.py (numpy, scipy, Pillow).
import numpy as np
from PIL import Image
from scipy.ndimage import gaussian_filter

src = np.asarray(Image.open('tests/data/flip/astronaut.png').convert('RGB'))
still = src[48:48 + 192, 112:112 + 256].copy()            # 256x192 crop: face, hair, collar ring

shifted = np.empty_like(still)                             # one pixel to the right,
shifted[:, 1:] = still[:, :-1]                             # the left edge column replicated
shifted[:, 0] = still[:, 0]

f = gaussian_filter(still.astype(np.float64), sigma=(1.5, 1.5, 0), mode='reflect', truncate=4.0)
blurred = np.clip(np.rint(f), 0, 255).astype(np.uint8)     # reflect = half-sample symmetric (dcba|abcd)

d = 'tests/data/cvvdp/'
Image.fromarray(still).save(d + 'still.png', optimize=True)
Image.fromarray(shifted).save(d + 'still_shift1.png', optimize=True)
Image.fromarray(blurred).save(d + 'still_blur1.5.png', optimize=True)
