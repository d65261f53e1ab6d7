// The app's CSS, injected into its own root element (host pages get no global stylesheet).
export const STYLE = `
.adasculpt-root { position: relative; width: 100%; height: 100%; overflow: hidden; outline: none;
  font: 12px/1.45 system-ui, -apple-system, "Segoe UI", sans-serif; color: #e6e8ec; background: #1c1e23;
  user-select: none; -webkit-user-select: none; }
.adasculpt-canvas { display: block; width: 100%; height: 100%; touch-action: none; }
.adasculpt-stats { position: absolute; left: 10px; top: 10px; padding: 6px 10px; border-radius: 6px;
  background: rgba(18, 20, 25, 0.72); font-variant-numeric: tabular-nums; pointer-events: none; }
.adasculpt-stats b { color: #fff; }
.adasculpt-stats .phases { color: #9aa3b2; font-size: 11px; }
.adasculpt-root .adasculpt-panel { position: absolute; right: 10px; top: 10px; max-height: calc(100% - 20px);
  overflow-y: auto; --widget-height: 18px; --spacing: 3px; --padding: 3px; }
.adasculpt-tools { position: absolute; left: 10px; top: calc(50% + 8px); transform: translateY(-50%); display: flex;
  flex-direction: column; gap: 2px; }
.adasculpt-tools button { font: inherit; font-size: 11px; line-height: 1.4; text-align: left; min-width: 84px;
  padding: 1px 7px; border-radius: 4px;
  border: 1px solid rgba(255, 255, 255, 0.12); background: rgba(18, 20, 25, 0.72); color: #cfd5df; cursor: pointer; }
.adasculpt-tools button:hover { background: rgba(45, 50, 62, 0.9); }
.adasculpt-tools button[aria-pressed="true"] { background: #d9822b; border-color: #ffb066; color: #fff; }
.adasculpt-tools .key { display: inline-block; width: 12px; margin-right: 6px; opacity: 0.6; }
.adasculpt-view { display: flex; flex-direction: column; gap: 2px; margin-top: 8px; }
.adasculpt-root .adasculpt-panel.compact { --widget-height: 16px; --spacing: 2px; --padding: 2px; font-size: 10px; }
.adasculpt-file { display: none; }
.adasculpt-drop { position: absolute; inset: 12px; display: none; align-items: center; justify-content: center;
  border: 2px dashed #7fb2ff; border-radius: 12px; background: rgba(30, 60, 110, 0.35); font-size: 18px;
  pointer-events: none; }
.adasculpt-drop.show { display: flex; }
.adasculpt-toasts { position: absolute; left: 10px; right: var(--adasculpt-inset, 10px); bottom: 58px; display: flex;
  flex-direction: column; align-items: center; gap: 6px; pointer-events: none; }
.adasculpt-toast { max-width: 100%; box-sizing: border-box; padding: 8px 14px; border-radius: 6px; background: rgba(30, 33, 40, 0.94);
  box-shadow: 0 2px 12px rgba(0, 0, 0, 0.45); }
.adasculpt-toast.error { background: rgba(160, 32, 38, 0.96); color: #fff; }
.adasculpt-help { position: absolute; left: 10px; bottom: 8px; max-width: calc(100% - var(--adasculpt-inset, 10px) - 36px); padding: 3px 8px; border-radius: 4px;
  background: rgba(18, 20, 25, 0.5); color: #aab2c0; font-size: 11px; pointer-events: none; }
`;
