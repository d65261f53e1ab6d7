// The numbers in the corner: fps while something animates, the last frame split into the core's
// phases plus the upload (render-buffer update in wasm, copy of the dirty ranges, render call),
// and the mesh figures.
export function createStatsOverlay(parent) {
  const el = document.createElement('div');
  el.className = 'adasculpt-stats';
  parent.appendChild(el);
  let frames = [];
  let fps = 0;
  const data = { vertices: 0, faces: 0, minAngle: null, meanMinAngle: null, timings: null, uploadMs: 0 };

  function fmt(x, digits = 1) { return x === null || x === undefined ? '–' : Number(x).toFixed(digits); }

  function render() {
    const t = data.timings;
    const phases = t
      ? `roi ${fmt(t.roi, 2)} · field ${fmt(t.field, 2)} · refine ${fmt(t.refine, 2)} · deform ${fmt(t.deform, 2)} · remesh ${fmt(t.remesh, 2)}`
      : '';
    el.innerHTML =
      `<div><b>${fps ? fps.toFixed(0) : '–'}</b> fps · frame <b>${t ? fmt(t.total + data.uploadMs, 2) : '–'}</b> ms` +
      (t ? ` (core ${fmt(t.total, 2)} + upload ${fmt(data.uploadMs, 2)})` : '') + '</div>' +
      (phases ? `<div class="phases">${phases}</div>` : '') +
      `<div>${data.vertices.toLocaleString('en-US')} vertices · ${data.faces.toLocaleString('en-US')} faces</div>` +
      `<div>min angle ${fmt(data.minAngle)}° · mean min angle ${fmt(data.meanMinAngle)}°</div>`;
  }
  render();

  return {
    element: el,
    // Called for every rendered frame of an interaction; fps over the last second.
    tick(now) {
      frames.push(now);
      while (frames.length && frames[0] < now - 1000) frames.shift();
      fps = frames.length > 1 ? (1000 * (frames.length - 1)) / (now - frames[0]) : 0;
    },
    idle() { frames = []; fps = 0; render(); },
    update(patch) { Object.assign(data, patch); render(); },
    dispose() { el.remove(); },
  };
}
