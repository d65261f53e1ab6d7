// The one place the front end keeps its defaults and reads lengths. The remeshing defaults (epsilon,
// min/max length) are the core's (Module.defaultSettings(), from cpp/remesh/remesher.h); these are
// the tools' own, shared by AdaptiveSculptor and the app's panel.
//
// A length is a number (absolute, in the mesh's own units) or a string "x%" (percent of the
// mesh's bounding-box diagonal), everywhere: options, setParams, <adasculpt-viewer> attributes.
export const TOOL_DEFAULTS = Object.freeze({
  tool: 'draw',
  radius: '5%',        // brushes
  strength: 0.5,       // 0..1
  symmetry: 'x',       // mirror across x = 0 (the mesh's own coordinates); 'off' for none
  handleRadius: '4%',  // the Pull tool (handle grab): handle and region of interest
  roiRadius: '15%',
});

export const SYMMETRY = ['x', 'y', 'z', 'off'];

// Ranges the keys and the panel keep the tool lengths in, percent of the diagonal.
export const RADIUS_RANGE_PCT = [0.5, 30];
export const ROI_RANGE_PCT = [1, 80];

// A length as percent of the diagonal: "x%" as written, a number converted. Throws naming `what`.
export function lengthToPercent(v, diagonal, what) {
  const text = typeof v === 'string' ? v.trim() : null;
  const pct = text !== null && text.endsWith('%');
  const x = pct ? Number(text.slice(0, -1)) : typeof v === 'number' ? v : NaN;
  if (!Number.isFinite(x) || x <= 0 || (pct && text.length < 2)) {
    throw new Error(`${what} must be a positive number or "x%" (got ${JSON.stringify(v)})`);
  }
  return pct ? x : (x / diagonal) * 100;
}

// An attribute's text ("0.1%" or "0.002") as a length value: percent strings stay strings.
export function lengthFromText(text) {
  const t = String(text).trim();
  return t.endsWith('%') ? t : Number(t);
}

export function checkStrength(v, what = 'strength') {
  if (typeof v !== 'number' || !(v >= 0 && v <= 1)) throw new Error(`${what} must be a number between 0 and 1`);
  return v;
}

// 'none', false and null read as 'off' (the core's word is 'none').
export function checkSymmetry(v) {
  const s = v === 'none' || v === false || v === null ? 'off' : v;
  if (!SYMMETRY.includes(s)) throw new Error(`symmetry must be one of ${SYMMETRY.join(', ')}`);
  return s;
}
