// Usage: node check.mjs FILE.glb
// Prints one JSON object: the Khronos validator's error and warning counts (with the first
// messages), and what three.js's GLTFLoader loaded: mesh names, the scene's bounding box, and
// each named node's lowest and highest point (metres, Y up), so heights can be checked.
import fs from 'fs';
import validator from 'gltf-validator';
import * as THREE from 'three';
import { GLTFLoader } from 'three/examples/jsm/loaders/GLTFLoader.js';

const file = process.argv[2];
const bytes = fs.readFileSync(file);
const report = await validator.validateBytes(new Uint8Array(bytes));
const ab = bytes.buffer.slice(bytes.byteOffset, bytes.byteOffset + bytes.byteLength);
const gltf = await new GLTFLoader().parseAsync(ab, '');
const box = new THREE.Box3().setFromObject(gltf.scene);
const meshes = [];
gltf.scene.traverse((o) => { if (o.isMesh) meshes.push(o.name); });
const heights = {};
gltf.scene.traverse((o) => {
  if (!o.name) return;
  const b = new THREE.Box3().setFromObject(o);
  if (!b.isEmpty()) heights[o.name] = [b.min.y, b.max.y];
});
console.log(JSON.stringify({
  errors: report.issues.numErrors,
  warnings: report.issues.numWarnings,
  messages: report.issues.messages.slice(0, 5),
  meshes,
  min: box.min.toArray(),
  max: box.max.toArray(),
  heights,
}));
