import sys, numpy as np
sys.path.insert(0, '/work/wt-bunnyrel/bench')
from peers_image import read, errors
ref = read('/tmp/bunny-ref-4k.exr')
w = 1.0 / (ref**2 + 0.01)
def rel_var(a, b):  # relMSE of one image estimated from two independent seeds
    return float(np.mean((a - b)**2 / 2 * w))
full = [read(f'wp-rr1-{n}.exr') for n in (1, 2)]
print('full rr1 by seeds 1,2: %.5f' % rel_var(*full))
m = [read(f'mts-{n}.exr') for n in (1, 2)]; print('mitsuba by seeds 1,2: %.5f' % rel_var(*m))
r5 = [read(f'wp-rr5-{n}.exr') for n in (1, 2)]; print('rr5 by seeds 1,2: %.5f' % rel_var(*r5))
for t in ('camera', 'direct', 'indirect'):
    p = [read(f'wp-rr1-{t}-{n}.exr') for n in (1, 2)]
    print(f'{t}: relvar %.5f, mean share of the reference %.3f' % (rel_var(*p), float(np.mean((p[0]+p[1])/2)) / float(np.mean(ref))))
# depth: share of mean by max depth (seed 1)
prev = 0
for d in (1, 2, 3, 4):
    a = read(f'wp-rr1-maxd{d}-1.exr'); print(f'rr1 depth<= {d}: mean share %.3f' % (float(np.mean(a))/float(np.mean(full[0]))))
# typical interior: pixels with ref < 0.2
mask = ref.mean(axis=-1) < 0.2 if ref.ndim == 3 else ref < 0.2
print('dark pixel share', mask.mean())
