// The sculpting mask from JavaScript (sculptor.mask, app.mask): the core's mask operations
// (cpp/sculpt/mask.h), each one undo step. Fully masked vertices never move under any tool and
// the remesher leaves their triangles alone; partly masked ones move by (1 - mask).
//
// The pointer's mask brush is the BrushTool with the tool 'mask': a press starts begin() (Ctrl or
// Alt held: erase), each frame's surface points go in one stamp() call, the release ends it.
// The whole-mask operations (clear, fill, invert, blur, sharpen) go through the same stroke life
// cycle, so they dispatch start/end like a stroke (the app autosaves on end).

export const MASK_OPS = ['clear', 'fill', 'invert', 'blur', 'sharpen'];

// session: the embind Session; stroke: the sculptor's {begin(kind, fn), frame(changes), end(fn)};
// defaults(): {radius (absolute), strength}; values(): the render buffers' mask per vertex slot.
export function createMaskApi({ session, stroke, defaults }) {
  const settings = (s) => {
    const d = defaults();
    return { op: s.erase ? 'erase' : 'paint', radius: s.radius ?? d.radius, strength: s.strength ?? d.strength };
  };
  const api = {
    // A paint (or, with erase: true, erase) stroke as the pointer moves: begin, stamp per frame, end.
    begin(s = {}) {
      const op = settings(s);
      stroke.begin('mask', () => session.maskBegin(op));
    },
    // points: [x, y, z, ...] surface points (array or typed array), a frame's worth in one call.
    stamp(points) {
      const ch = session.maskStamp(points instanceof Float64Array ? points : Float64Array.from(points));
      stroke.frame(ch);
      return { vertices: ch.vertices, faces: ch.faces, timings: ch.timings };
    },
    end() {
      stroke.end(() => session.maskEnd());
    },
    // A whole stroke: path [[x, y, z], ...] of surface points; erase, radius, strength optional.
    stroke({ path, ...s } = {}) {
      if (!Array.isArray(path) || path.length === 0) throw new Error('mask.stroke: path must be a non-empty array of [x, y, z]');
      const points = new Float64Array(3 * path.length);
      path.forEach((p, i) => {
        const q = Array.isArray(p) ? p : [p?.x, p?.y, p?.z];
        if (q.length !== 3 || !q.every(Number.isFinite)) throw new Error(`mask.stroke: path[${i}] must be [x, y, z]`);
        points.set(q, 3 * i);
      });
      api.begin(s);
      try {
        return api.stamp(points);
      } finally {
        api.end();
      }
    },
    // The mask value of every vertex slot (a copy; 0 where unmasked or deleted).
    values() {
      return session.maskValues().slice();
    },
  };
  for (const op of MASK_OPS) {
    api[op] = () => {
      stroke.begin('mask', () => stroke.frame(session.mask({ op })));
      stroke.end(() => {});
    };
  }
  return api;
}
