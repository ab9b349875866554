"""Point labels that do not overlap: each label tries offsets around its point, nearest
first, and takes the first whose box is inside the axes and clear of the labels placed
before it and of every marker; when none is clear it takes the least covered one, so a
label is never dropped. Place labels after the figure's layout is final (tight_layout
moves the axes, not the offsets), and save without another tight_layout."""

# Offsets in points, nearest ring first: right, above, left, below, then the diagonals.
_DIRECTIONS = ((1, 0), (0, 1), (-1, 0), (0, -1), (1, 1), (-1, 1), (-1, -1), (1, -1))
_RINGS = (4, 9, 15, 22, 30)
_MARKER_PX = 4.0  # half the side of the box kept clear around each marker


def _overlap(a, b):
    w = min(a.x1, b.x1) - max(a.x0, b.x0)
    h = min(a.y1, b.y1) - max(a.y0, b.y0)
    return w * h if w > 0 and h > 0 else 0.0


def _marker_boxes(ax, points):
    from matplotlib.transforms import Bbox
    boxes = []
    for x, y in points:
        px, py = ax.transData.transform((x, y))
        boxes.append(Bbox([[px - _MARKER_PX, py - _MARKER_PX], [px + _MARKER_PX, py + _MARKER_PX]]))
    return boxes


def place_labels(ax, labelled, fontsize=7, avoid=(), avoid_boxes=()):
    """labelled: [(x, y, text)] in data coordinates; avoid: further (x, y) markers to keep
    clear; avoid_boxes: window boxes to keep clear (a legend). The texts already on the
    axes are kept clear too. Adds one annotation per entry and returns [(text, annotation)]."""
    fig = ax.figure
    renderer = fig.canvas.get_renderer()
    frame = ax.get_window_extent(renderer)
    pts = [(x, y) for x, y, _ in labelled]
    obstacles = _marker_boxes(ax, pts + list(avoid)) + list(avoid_boxes) + [t.get_window_extent(renderer) for t in ax.texts]
    placed = []
    out = []
    for x, y, text in labelled:
        best = None
        for ring in _RINGS:
            for dx, dy in _DIRECTIONS:
                ann = ax.annotate(text, (x, y), xytext=(dx * ring, dy * ring), textcoords="offset points", fontsize=fontsize,
                                  ha="left" if dx > 0 else "right" if dx < 0 else "center",
                                  va="bottom" if dy > 0 else "top" if dy < 0 else "center")
                box = ann.get_window_extent(renderer)
                inside = frame.x0 <= box.x0 and box.x1 <= frame.x1 and frame.y0 <= box.y0 and box.y1 <= frame.y1
                cover = sum(_overlap(box, b) for b in placed + obstacles) + (0 if inside else 1e9)
                if best is None or cover < best[0]:
                    if best is not None:
                        best[1].remove()
                    best = (cover, ann, box, ring)
                else:
                    ann.remove()
                if cover == 0:
                    break
            if best[0] == 0:
                break
        _, ann, box, ring = best
        if ring > _RINGS[0]:  # a displaced label points at its marker
            ann.remove()
            ann = ax.annotate(text, (x, y), xytext=ann.xyann, textcoords="offset points", fontsize=fontsize,
                              ha=ann.get_ha(), va=ann.get_va(),
                              arrowprops={"arrowstyle": "-", "color": "0.5", "linewidth": 0.5, "shrinkA": 0, "shrinkB": 2})
        placed.append(box)
        out.append((text, ann))
    return out


def label_boxes(ax, annotations):
    """The window boxes of the annotations' texts (tests check they do not overlap)."""
    renderer = ax.figure.canvas.get_renderer()
    return [ann.get_window_extent(renderer) for _, ann in annotations]
