"""The convergence plot of bench/peers.py: error against time, log-log, one
line per renderer and mode, as a self-contained SVG."""
import math
from xml.sax.saxutils import escape

COLOURS = ["#1f77b4", "#d62728", "#2ca02c", "#ff7f0e", "#9467bd", "#8c564b", "#e377c2", "#17becf"]


def _decades(low, high):
    return list(range(math.floor(math.log10(low)), math.ceil(math.log10(high)) + 1))


def write_svg(path, series, title, x_label, y_label):
    """series: [{"label", "points": [(x, y, spp)], "dashed"}]; x and y > 0."""
    xs = [p[0] for s in series for p in s["points"] if p[0] > 0 and p[1] > 0]
    ys = [p[1] for s in series for p in s["points"] if p[0] > 0 and p[1] > 0]
    width, height, left, right, top, bottom = 760, 500, 70, 250, 40, 50
    if not xs:
        open(path, "w").write(f'<svg xmlns="http://www.w3.org/2000/svg" width="{width}" height="80">'
                              f'<text x="10" y="40">{escape(title)}: no points</text></svg>\n')
        return
    x_decades, y_decades = _decades(min(xs), max(xs)), _decades(min(ys), max(ys))
    x0, x1 = x_decades[0], max(x_decades[-1], x_decades[0] + 1)
    y0, y1 = y_decades[0], max(y_decades[-1], y_decades[0] + 1)
    plot_w, plot_h = width - left - right, height - top - bottom

    def px(x):
        return left + (math.log10(x) - x0) / (x1 - x0) * plot_w

    def py(y):
        return top + (y1 - math.log10(y)) / (y1 - y0) * plot_h

    out = [f'<svg xmlns="http://www.w3.org/2000/svg" width="{width}" height="{height}" '
           f'font-family="sans-serif" font-size="12">',
           f'<rect width="{width}" height="{height}" fill="white"/>',
           f'<text x="{left}" y="22" font-size="14">{escape(title)}</text>',
           f'<rect x="{left}" y="{top}" width="{plot_w}" height="{plot_h}" fill="none" stroke="black"/>']
    for d in range(x0, x1 + 1):
        x = px(10.0 ** d)
        out.append(f'<line x1="{x:.1f}" y1="{top}" x2="{x:.1f}" y2="{top + plot_h}" stroke="#ddd"/>')
        out.append(f'<text x="{x:.1f}" y="{top + plot_h + 16}" text-anchor="middle">{10.0 ** d:g}</text>')
    for d in range(y0, y1 + 1):
        y = py(10.0 ** d)
        out.append(f'<line x1="{left}" y1="{y:.1f}" x2="{left + plot_w}" y2="{y:.1f}" stroke="#ddd"/>')
        out.append(f'<text x="{left - 6}" y="{y + 4:.1f}" text-anchor="end">{10.0 ** d:g}</text>')
    out.append(f'<text x="{left + plot_w / 2}" y="{height - 12}" text-anchor="middle">{escape(x_label)}</text>')
    out.append(f'<text x="16" y="{top + plot_h / 2}" text-anchor="middle" '
               f'transform="rotate(-90 16 {top + plot_h / 2})">{escape(y_label)}</text>')
    for index, s in enumerate(series):
        colour = COLOURS[index % len(COLOURS)]
        points = [p for p in s["points"] if p[0] > 0 and p[1] > 0]
        dash = ' stroke-dasharray="6 4"' if s.get("dashed") else ""
        coordinates = " ".join(f"{px(p[0]):.1f},{py(p[1]):.1f}" for p in points)
        out.append(f'<polyline points="{coordinates}" fill="none" stroke="{colour}" stroke-width="2"{dash}/>')
        for p in points:
            out.append(f'<circle cx="{px(p[0]):.1f}" cy="{py(p[1]):.1f}" r="3" fill="{colour}">'
                       f'<title>{escape(s["label"])}: {p[2]} spp, {p[0]:.3g} s, {p[1]:.3g}</title></circle>')
        ly = top + 14 + 18 * index
        out.append(f'<line x1="{left + plot_w + 12}" y1="{ly - 4}" x2="{left + plot_w + 36}" y2="{ly - 4}" '
                   f'stroke="{colour}" stroke-width="2"{dash}/>')
        out.append(f'<text x="{left + plot_w + 42}" y="{ly}">{escape(s["label"])}</text>')
    out.append("</svg>")
    with open(path, "w") as file:
        file.write("\n".join(out) + "\n")
