// How a brush feels and how fine it sculpts (issue 19): the falloff preset, the stamp spacing, the
// stroke stabiliser (lazy mouse) and the detail mode with its three sizes. One place for their
// defaults, checks and the stroke's detail length, shared by AdaptiveSculptor (setParams/params) and
// the app's panel.
//
// Detail modes (the edge length a stroke remeshes to; the whole-mesh "detail flood fill" uses it too):
//   'relative' the remesh settings (epsilon, min/max length): detail follows the curvature (default)
//   'constant' a fixed edge length, constantDetail ("x%" of the diagonal or absolute)
//   'brush'    brushDetail percent of the brush radius (a small brush sculpts finer)
//   'pixels'   pixelDetail screen pixels at the brush (zoom in for finer detail)

export const FALLOFFS = ['smooth', 'sphere', 'sharp', 'linear', 'constant'];
export const DETAIL_MODES = ['relative', 'constant', 'brush', 'pixels'];

export const FEEL_DEFAULTS = Object.freeze({
  falloff: 'smooth',        // the core's (1 - q^2)^3: every stroke before presets
  spacing: 0.25,            // a stamp every spacing x radius of travel (the core's default)
  stabilizer: 0,            // lazy-mouse string length in screen pixels; 0: off
  detailMode: 'relative',
  constantDetail: '0.8%',   // percent of the diagonal (a number: absolute)
  brushDetail: 15,          // percent of the brush radius
  pixelDetail: 8,           // screen pixels
});
export const FEEL_KEYS = Object.keys(FEEL_DEFAULTS);

// The spacing range the core accepts (cpp/deform/brushes.cpp check_brush_settings); the panel's
// slider stops at 1 (sparser stamps leave dents).
export const SPACING_RANGE = [0.05, 4];
export const STABILIZER_MAX_PX = 200;
const BRUSH_DETAIL_RANGE = [1, 100];
const PIXEL_DETAIL_RANGE = [1, 100];

function inRange(key, v, [lo, hi], unit = '') {
  if (typeof v !== 'number' || !(v >= lo && v <= hi)) throw new Error(`setParams: ${key} must be a number between ${lo} and ${hi}${unit}`);
  return v;
}

// Checks one feel parameter; returns the value to keep (constantDetail as percent of the diagonal).
export function checkFeel(key, v, diagonal, lengthToPercent) {
  switch (key) {
    case 'falloff':
      if (!FALLOFFS.includes(v)) throw new Error(`setParams: falloff must be one of ${FALLOFFS.join(', ')}`);
      return v;
    case 'detailMode':
      if (!DETAIL_MODES.includes(v)) throw new Error(`setParams: detailMode must be one of ${DETAIL_MODES.join(', ')}`);
      return v;
    case 'spacing': return inRange(key, v, SPACING_RANGE, ' (fraction of the radius)');
    case 'stabilizer': return inRange(key, v, [0, STABILIZER_MAX_PX], ' (pixels; 0: off)');
    case 'brushDetail': return inRange(key, v, BRUSH_DETAIL_RANGE, ' (percent of the radius)');
    case 'pixelDetail': return inRange(key, v, PIXEL_DETAIL_RANGE, ' (pixels)');
    case 'constantDetail': return lengthToPercent(v, diagonal, 'constantDetail');
    default: throw new Error(`setParams: unknown parameter '${key}'`);
  }
}

// The edge length (absolute) a stroke or a flood fill remeshes to; 0: the remesh settings.
// feel: the checked values (constantDetail in percent); pixelSize(): the world size of a screen
// pixel where the brush is (only asked in 'pixels' mode).
export function detailLength(feel, { diagonal, radius, pixelSize }) {
  switch (feel.detailMode) {
    case 'constant': return (feel.constantDetail / 100) * diagonal;
    case 'brush': return (feel.brushDetail / 100) * radius;
    case 'pixels': return feel.pixelDetail * pixelSize();
    default: return 0;
  }
}
