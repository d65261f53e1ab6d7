// Which tool the pointer drives: the handle grab (GrabTool) or one of the brushes (BrushTool).
// Buttons on the left edge show the choice (aria-pressed); the digit keys 1-8 pick a tool.
// A tool cannot change while a grab or a stroke is under way.
import { TOOLS } from './brush-tool.js';
import { isTextInput } from './tool-events.js';

export class ToolPalette {
  // parent: where the buttons go (null: keyboard and API only); onChange(name) after a switch.
  constructor(parent, keyTarget, { grabTool, brushTool, state, onChange }) {
    this.grabTool = grabTool;
    this.brushTool = brushTool;
    this.state = state;
    this.onChange = onChange;
    this.buttons = new Map();
    this.el = null;
    if (parent) {
      this.el = document.createElement('div');
      this.el.className = 'adasculpt-tools';
      this.el.setAttribute('role', 'toolbar');
      for (const t of TOOLS) {
        const b = document.createElement('button');
        b.type = 'button';
        b.dataset.tool = t.name;
        b.title = `${t.label} (${t.key}): ${t.title}`;
        b.innerHTML = `<span class="key">${t.key}</span>${t.label}`;
        b.addEventListener('click', () => this.setTool(t.name));
        this.buttons.set(t.name, b);
        this.el.appendChild(b);
      }
      parent.appendChild(this.el);
    }
    this.keyTarget = keyTarget;
    this.onKey = (e) => {
      if (e.ctrlKey || e.metaKey || e.altKey || isTextInput(e.target)) return;
      const t = TOOLS.find((x) => x.key === e.key);
      if (t && this.setTool(t.name)) e.preventDefault();
    };
    keyTarget.addEventListener('keydown', this.onKey);
    this.setTool(state.tool || 'pull');
  }

  get tool() { return this.state.tool; }

  // Returns false (and changes nothing) while a grab or stroke runs; throws on an unknown name.
  setTool(name) {
    if (!TOOLS.some((t) => t.name === name)) {
      throw new Error(`setTool: unknown tool '${name}' (${TOOLS.map((t) => t.name).join(', ')})`);
    }
    if (this.grabTool.active || this.brushTool.active) return false;
    this.state.tool = name;
    this.grabTool.setEnabled(name === 'pull');
    this.brushTool.setEnabled(name !== 'pull');
    for (const [n, b] of this.buttons) b.setAttribute('aria-pressed', String(n === name));
    if (this.onChange) this.onChange(name);
    return true;
  }

  dispose() {
    this.keyTarget.removeEventListener('keydown', this.onKey);
    if (this.el) this.el.remove();
  }
}
