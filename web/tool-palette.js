// The tool buttons on the left edge (aria-pressed shows the current tool), the digit keys 1-8 and M.
// The sculptor decides: setTool(name) returns false while a grab or stroke is under way.
import { TOOLS } from './brush-tool.js';
import { isTextInput } from './tool-events.js';

export class ToolPalette {
  // parent: where the buttons go (null: keyboard only); sculptor: the AdaptiveSculptor.
  constructor(parent, keyTarget, sculptor) {
    this.sculptor = sculptor;
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
        b.title = `${t.label} (${t.key.toUpperCase()}): ${t.title}`;
        b.innerHTML = `<span class="key">${t.key.toUpperCase()}</span>${t.label}`;
        b.addEventListener('click', () => sculptor.setTool(t.name));
        this.buttons.set(t.name, b);
        this.el.appendChild(b);
      }
      parent.appendChild(this.el);
    }
    this.keyTarget = keyTarget;
    this.onKey = (e) => {
      // The numpad's digits are view keys (web/view-controls.js), not tools.
      if (e.ctrlKey || e.metaKey || e.altKey || e.code?.startsWith('Numpad') || isTextInput(e.target)) return;
      const t = TOOLS.find((x) => x.key === e.key.toLowerCase()); // M or m
      if (t && sculptor.setTool(t.name)) e.preventDefault();
    };
    keyTarget.addEventListener('keydown', this.onKey);
    this.onTool = () => this.refresh();
    sculptor.addEventListener('tool', this.onTool);
    this.refresh();
  }

  refresh() {
    for (const [n, b] of this.buttons) b.setAttribute('aria-pressed', String(n === this.sculptor.tool));
  }

  dispose() {
    this.keyTarget.removeEventListener('keydown', this.onKey);
    this.sculptor.removeEventListener('tool', this.onTool);
    if (this.el) this.el.remove();
  }
}
