// The help bar's text: what a press does with the current tool, then the view's mouse and keys
// (true to web/grab-tool.js, web/brush-tool.js, OrbitControls and web/view-controls.js).
import { TOOLS } from './brush-tool.js';

const VIEW_HELP = 'drag off the model: orbit · middle drag: orbit around the point under it · right drag: pan · wheel: zoom · F frame · O ortho · Shift+1–6 views · Ctrl+Z / Ctrl+Shift+Z';

export function helpText(tool) {
  const t = TOOLS.find((x) => x.name === tool);
  const name = t ? t.label : tool;
  let what;
  if (tool === 'pull') what = 'Pull: drag on the model · during the drag R rotate, S scale, wheel scale · [ ] ROI · { } handle';
  else if (tool === 'mask') what = 'Mask: paint on the model · Ctrl/Alt erase · [ ] or Shift+wheel radius · - = strength · panel: clear, invert, blur, sharpen';
  else what = `${name}: stroke on the model · Ctrl/Alt invert · [ ] or Shift+wheel radius · - = strength`;
  return `${what} · 1 Pull, 2–8 brushes, M mask · ${VIEW_HELP}`;
}
