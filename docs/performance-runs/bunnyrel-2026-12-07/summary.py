# relMSE and MSE per set of seeds against the reference, the rays of each render (from the logs),
# relMSE by the reference's brightness and by wall; the colour walls' pixels.
import sys, glob, re, numpy as np
sys.path.insert(0, '/work/wt-bunnyrel/bench')
from peers_image import read
ref = read(sys.argv[1]); sets = sys.argv[2:]
w = 1.0 / (ref**2 + 0.01)
rays = {}
for log in glob.glob('/tmp/bunnyrel/renders*.log'):
    for m in re.finditer(r'rendered \S*/r/(\S+)\.exr: .*\((\d+) camera, (\d+) bounce, (\d+) shadow', open(log).read()):
        rays[m.group(1)] = sum(int(x) for x in m.groups()[1:])
lum = ref.mean(axis=-1)
for s in sets:
    files = sorted(glob.glob(f'/tmp/bunnyrel/r/{s}-[0-9].exr'))
    imgs = [read(f) for f in files]
    rel = [float(np.mean((x - ref)**2 * w)) for x in imgs]
    mse = [float(np.mean((x - ref)**2)) for x in imgs]
    pix = np.mean([((x - ref)**2 * w).mean(axis=-1) for x in imgs], axis=0)
    r = [rays.get(f.split('/')[-1][:-4]) for f in files]
    r = np.mean([x for x in r if x]) if any(r) else float('nan')
    print(f'{s:14s} n={len(imgs)} relMSE {np.mean(rel):.5f} (sd {np.std(rel):.5f}) MSE {np.mean(mse):.3e} rays {r/1e6:.2f}M '
          f'median px {np.median(pix):.5f}  right third {pix[:, 200:].mean():.5f} left third {pix[:, :56].mean():.5f} middle {pix[:, 80:176].mean():.5f}')
