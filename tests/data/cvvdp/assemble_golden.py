#!/usr/bin/env python3
# Gathers the cvvdp-golden outputs of make_golden.sh into golden.json (layout: README.md).
# Usage: assemble_golden.py RAW_DIR ATRIUM_OUT > golden.json
import json, os, re, sys

raw, atrium = sys.argv[1], os.path.normpath(sys.argv[2])
CASES = ['image-4k', 'image-fhd'] + ['atrium-' + v for v in ('drr', 'cbr-aso', 'cbr-cso', 'cbr-clip', 'taau')] \
    + ['flicker-30fps', 'blur-30fps', 'flicker-60fps']


def files(lst, n):
    # atrium frames: a printf pattern relative to the cbrbench run --out folder;
    # otherwise the distinct files in order, cycled to n frames
    if os.path.normpath(lst[0]).startswith(atrium + os.sep):
        rel = [os.path.relpath(f, atrium) for f in lst]
        pat = re.sub(r'_(\d{4})\.png$', '_%04d.png', rel[0])
        assert rel == [pat % i for i in range(n)], rel
        return pat
    cyc = []
    for f in lst:
        if f in cyc:
            break
        cyc.append(f)
    assert lst == [cyc[i % len(cyc)] for i in range(n)]
    return cyc


out = {'reference': None, 'pooling': None, 'cases': {}}
for name in CASES:
    d = json.load(open(os.path.join(raw, name + '.json')))
    if out['reference'] is None:
        out['reference'] = {
            'repository': 'https://github.com/gfxdisp/ColorVideoVDP',
            'commit': '7ca201accf7894f7c02e43122cd2e195755a7976',
            'parameters_version': d['reference_parameters_version'],
            'device': 'cpu', 'how': 'tests/data/cvvdp/README.md'}
        out['pooling'] = d['pooling']
    assert d['pooling']['channel_weights'][:3] == out['pooling']['channel_weights'][:3]
    if len(d['pooling']['channel_weights']) > len(out['pooling']['channel_weights']):
        out['pooling'] = d['pooling']
    out['cases'][name] = {
        'mode': d['mode'], 'display': d['display'], 'ppd': d['ppd'], 'fps': d['fps'],
        'width': d['width'], 'height': d['height'], 'frames': d['frames'],
        'ref': files(d['ref_files'], d['frames']), 'test': files(d['test_files'], d['frames']),
        'temporal_filter_len': d['temporal_filter_len'],
        'jod': d['jod'], 'jod_from_per_frame_Q': d['jod_from_per_frame_Q'],
        'per_frame_Q': d['per_frame_Q'], 'per_frame_JOD': d['per_frame_JOD'],
        'rho_band': d['rho_band'], 'Q_per_ch': d['Q_per_ch'],
    }


def dump(x, ind=0):
    sp = ' ' * ind
    if isinstance(x, dict):
        items = [f'{sp} {json.dumps(k)}: {dump(v, ind + 1)}' for k, v in x.items()]
        return '{\n' + ',\n'.join(items) + '\n' + sp + '}'
    if isinstance(x, list) and any(isinstance(e, (list, dict)) for e in x):
        return '[\n' + ',\n'.join(sp + ' ' + dump(e, ind + 1) for e in x) + '\n' + sp + ']'
    return json.dumps(x)


print(dump(out))
