#!/usr/bin/python3
"""Scores the JOD validation cases with the reference FovVideoVDP (docs/metrics.md, "JOD").

usage: /usr/bin/python3 run_reference.py FVVDP_DIR CASES_DIR OUT.csv [CSF_TABLES_DIR]

With CSF_TABLES_DIR (what make_csf_table.py 0.405835 wrote), the reference runs release
1.0's calibration (its own pyfvvdp/fvvdp_data/fvvdp_parameters_1_0.json) on those tables.

FVVDP_DIR holds the reference's pyfvvdp package (github:gfxdisp/FovVideoVDP, release 1.2.3,
commit 31254d0; CC BY-NC 4.0, run only, nothing of it is in foveal); CASES_DIR is what
jod_cases_write wrote (cases.json and the frames). Debian 12's python3-torch, -numpy, -scipy,
-imageio; imageio.v2 and ffmpeg (which the package imports but these stills and frame
lists never use) are stood in for. The display: FovVideoVDP's htc_vive_pro photometry
(133.3 / 0.1 cd/m², sRGB) and a geometry of the case's image size at 753.6 px focal length
(13.153 px/deg), foveal's vive_window_384x224 model
(tests/perception/data).
"""
import csv, json, math, os, sys, types

import imageio
import shutil
import tempfile
sys.modules.setdefault('imageio.v2', imageio)
if len(sys.argv) > 4:
    # Release 1.0: its parameter file under the name the package looks for (FVVDP_PATH), and
    # the tables it needs in ./csf_cache, the first place it looks.
    _cfg = tempfile.mkdtemp()
    shutil.copy(os.path.join(sys.argv[1], 'pyfvvdp', 'fvvdp_data', 'fvvdp_parameters_1_0.json'),
                os.path.join(_cfg, 'fvvdp_parameters.json'))
    os.environ['FVVDP_PATH'] = _cfg
    _run = tempfile.mkdtemp()
    shutil.copytree(sys.argv[4], os.path.join(_run, 'csf_cache'))
    sys.argv[1:4] = [os.path.abspath(a) for a in sys.argv[1:4]]
    os.chdir(_run)
sys.modules.setdefault('ffmpeg', types.ModuleType('ffmpeg'))
sys.path.insert(0, sys.argv[1])
import numpy as np
import torch
from pyfvvdp import fvvdp
from pyfvvdp.fvvdp_display_model import fvvdp_display_geometry

FOCAL_PX = 753.6


def frames(case_dir, names):
    return np.stack([imageio.imread(os.path.join(case_dir, n))[..., :3] for n in names])


def main():
    fv_dir, cases_dir, out_path = sys.argv[1:4]
    cases = json.load(open(os.path.join(cases_dir, 'cases.json')))
    torch.set_num_threads(2)
    rows = []
    metrics = {}
    for c in cases:
        ref = frames(cases_dir, c['ref'])
        test = frames(cases_dir, c['test'])
        f, h, w, _ = ref.shape
        foveated = c['fovea'] is not None
        key = (w, h, foveated)
        if key not in metrics:
            geo = fvvdp_display_geometry((w, h), distance_m=3, fov_horizontal=2 * math.degrees(math.atan(w / 2 / FOCAL_PX)))
            metrics[key] = fvvdp(display_name='htc_vive_pro', display_geometry=geo, foveated=foveated, quiet=True)
        m = metrics[key]
        fix = None
        if foveated:
            # Pixels; the reference adds half a pixel to the fixation it is given. A list of
            # [x, y] per frame is one fixation per frame.
            g = np.array(c['fovea'], dtype=float)
            fix = torch.tensor(np.stack([g[..., 0] * w - 0.5, g[..., 1] * h - 0.5], -1))
        if f == 1:
            q, _ = m.predict(test[0], ref[0], dim_order='HWC', fixation_point=fix)
        else:
            q, _ = m.predict(test, ref, dim_order='FHWC', frames_per_second=c['fps'], fixation_point=fix)
        rows.append({'name': c['name'], 'frames': f, 'jod': '%.5f' % float(q)})
        print(c['name'], rows[-1]['jod'], flush=True)
    with open(out_path + '.tmp', 'w', newline='') as fh:
        wr = csv.DictWriter(fh, fieldnames=['name', 'frames', 'jod'])
        wr.writeheader()
        wr.writerows(rows)
    os.replace(out_path + '.tmp', out_path)


if __name__ == '__main__':
    main()
