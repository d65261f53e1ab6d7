// The brush cursor: a ring lying on the surface at the hit point (its plane perpendicular to the
// surface normal), as wide as the brush radius, with an inner ring showing the strength. Drawn over
// the surface (no depth test) so a curved surface cannot hide half of it; orange when the brush
// adds, blue when it is inverted. A child of the sculpted mesh: it lives in the mesh's own
// coordinates, like the core's positions and radii.
import * as THREE from 'three';

const ADD_COLOR = new THREE.Color(1.0, 0.62, 0.25);
const INVERT_COLOR = new THREE.Color(0.35, 0.7, 1.0);
const Z = new THREE.Vector3(0, 0, 1);

function circle(segments) {
  const pts = new Float32Array(3 * segments);
  for (let i = 0; i < segments; i++) {
    const a = (i / segments) * Math.PI * 2;
    pts[3 * i] = Math.cos(a);
    pts[3 * i + 1] = Math.sin(a);
  }
  return new THREE.BufferGeometry().setAttribute('position', new THREE.BufferAttribute(pts, 3));
}

export class BrushCursor {
  // parent: the sculpted mesh; changed(): something to draw changed (the host renders).
  constructor(parent, changed) {
    this.parent = parent;
    this.changed = changed;
    this.geometry = circle(72);
    const material = () => new THREE.LineBasicMaterial({ color: ADD_COLOR, transparent: true, depthTest: false, depthWrite: false });
    this.outer = new THREE.LineLoop(this.geometry, material());
    this.inner = new THREE.LineLoop(this.geometry, material());
    this.inner.material.opacity = 0.45;
    this.group = new THREE.Group();
    this.group.add(this.outer, this.inner);
    this.group.renderOrder = this.outer.renderOrder = this.inner.renderOrder = 10;
    this.group.visible = false;
    parent.add(this.group);
  }

  // Where and how big; null point hides it.
  show(point, normal, radius, strength, inverted) {
    const g = this.group;
    if (!point) {
      if (g.visible) { g.visible = false; this.changed(); }
      return;
    }
    g.visible = true;
    g.position.copy(point);
    g.quaternion.setFromUnitVectors(Z, normal);
    this.outer.scale.setScalar(radius);
    this.inner.scale.setScalar(radius * Math.max(0.05, strength));
    const c = inverted ? INVERT_COLOR : ADD_COLOR;
    this.outer.material.color.copy(c);
    this.inner.material.color.copy(c);
    this.changed();
  }

  get visible() { return this.group.visible; }
  get center() { return this.group.position; }
  get radius() { return this.outer.scale.x; }

  dispose() {
    this.parent.remove(this.group);
    this.geometry.dispose();
    this.outer.material.dispose();
    this.inner.material.dispose();
  }
}
