# relMSE per pixel grouped by the camera ray's first surface (albedo AOV): white, red wall, green wall, light.
import sys, glob, numpy as np
import mitsuba as mi
mi.set_variant('scalar_rgb')
sys.path.insert(0, '/work/wt-bunnyrel/bench')
from peers_image import read
a = np.array(mi.Bitmap('/tmp/bunnyrel/aov.exr'))[..., 3:6]
ref = read('/tmp/bunny-ref-4k.exr'); w = 1.0 / (ref**2 + 0.01)
groups = {'white': np.isclose(a[..., 1], 0.73, atol=0.02) & np.isclose(a[..., 0], 0.73, atol=0.02),
          'red wall': np.isclose(a[..., 0], 0.63, atol=0.02) & (a[..., 1] < 0.2),
          'green wall': np.isclose(a[..., 1], 0.45, atol=0.02) & (a[..., 0] < 0.3)}
groups['other (edges, light)'] = ~(groups['white'] | groups['red wall'] | groups['green wall'])
print('| set | ' + ' | '.join(f'{g} ({m.sum()} px)' for g, m in groups.items()) + ' |')
for s in sys.argv[1:]:
    imgs = [read(f) for f in sorted(glob.glob(f'/tmp/bunnyrel/r/{s}-[0-9].exr'))]
    pix = np.mean([((x - ref)**2 * w).mean(axis=-1) for x in imgs], axis=0)
    print(f'| {s} | ' + ' | '.join(f'{pix[m].mean():.5f} ({pix[m].sum()/pix.sum():.2f})' for m in groups.values()) + ' |')
