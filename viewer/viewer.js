// octomotion's viewer: shows a .glb from `octomotion view` (tools/src/gltf_export.cpp):
// the environment voxels, each link's moved voxel tree, the robot, and the path animation
// ("path": state i at time i s) stepped with a slider or played.
// window.octomotionViewer exposes the state for scripts and the end-to-end test.
import * as THREE from 'three';
import { GLTFLoader } from 'three/addons/loaders/GLTFLoader.js';
import { OrbitControls } from 'three/addons/controls/OrbitControls.js';

const params = new URLSearchParams(window.location.search);
const modelUrl = params.get('model') || 'scene.glb';
const stateParam = params.get('state') || '0';  // a state index, or 'last'
let initialState = 0;
const statesPerSecond = 4;
const background = 0xeef1f5;

const container = document.getElementById('view');
const slider = document.getElementById('slider');
const playButton = document.getElementById('play');
const stateLabel = document.getElementById('state-label');
const statusLine = document.getElementById('status');

// preserveDrawingBuffer: the canvas can be read back (screenshots, the end-to-end test).
const renderer = new THREE.WebGLRenderer({ antialias: true, preserveDrawingBuffer: true });
renderer.setPixelRatio(window.devicePixelRatio);
renderer.setSize(container.clientWidth, container.clientHeight);
container.appendChild(renderer.domElement);

const scene = new THREE.Scene();
scene.background = new THREE.Color(background);
scene.add(new THREE.HemisphereLight(0xffffff, 0x8a8f99, 1.6));
const sun = new THREE.DirectionalLight(0xffffff, 1.8);
sun.position.set(2, 4, 3);
scene.add(sun);

const camera = new THREE.PerspectiveCamera(40, container.clientWidth / container.clientHeight,
                                           0.01, 1000);
const controls = new OrbitControls(camera, renderer.domElement);
controls.addEventListener('change', render);

const viewer = {
  ready: false,
  error: null,
  stateCount: 0,
  state: 0,
  playing: false,
  groups: {},  // environment_voxels, link_voxels, robot
  clip: null,  // the "path" animation
  renderer, scene, camera,
  setState, setVisible, render, play, pause,
};
window.octomotionViewer = viewer;

let mixer = null;
let action = null;
let playTime = 0;
const clock = new THREE.Clock();

function render() {
  renderer.render(scene, camera);
}

function setState(i) {
  const last = Math.max(0, viewer.stateCount - 1);
  const t = Math.min(Math.max(i, 0), last);
  viewer.state = t;
  if (action) {
    // Drive the action's time directly: a looping action would wrap the last state to the
    // first, and a finished LoopOnce action pauses itself.
    action.enabled = true;
    action.paused = false;
    action.time = t;
    mixer.update(0);
  }
  slider.value = String(Math.round(t));
  stateLabel.textContent = `state ${Math.round(t)} / ${last}`;
  render();
}

function setVisible(name, visible) {
  const g = viewer.groups[name];
  if (g) g.visible = visible;
  const box = document.querySelector(`input[data-group="${name}"]`);
  if (box) box.checked = visible;
  render();
}

function play() {
  if (viewer.stateCount < 2) return;
  if (viewer.state >= viewer.stateCount - 1) playTime = 0; else playTime = viewer.state;
  viewer.playing = true;
  playButton.textContent = 'Pause';
  clock.getDelta();
  requestAnimationFrame(tick);
}

function pause() {
  viewer.playing = false;
  playButton.textContent = 'Play';
}

function tick() {
  if (!viewer.playing) return;
  playTime += clock.getDelta() * statesPerSecond;
  if (playTime >= viewer.stateCount - 1) {
    setState(viewer.stateCount - 1);
    pause();
    return;
  }
  setState(playTime);
  requestAnimationFrame(tick);
}

function swatch(material) {
  const c = material.color.getStyle();
  return `<span class="swatch" style="background:${c};opacity:${Math.max(material.opacity, 0.5)}"></span>`;
}

function addLayerToggle(name, label, material) {
  const row = document.createElement('label');
  row.innerHTML = `<input type="checkbox" data-group="${name}" checked> ` +
                  (material ? swatch(material) : '') + label;
  row.querySelector('input').addEventListener('change', (e) => setVisible(name, e.target.checked));
  document.getElementById('layers').appendChild(row);
}

function firstMaterial(object) {
  let found = null;
  object.traverse((o) => { if (!found && o.isMesh) found = o.material; });
  return found;
}

// Looks at the whole model from the front left, above (robot frame: from -x and -y).
function frame(object) {
  const box = new THREE.Box3().setFromObject(object);
  const size = box.getSize(new THREE.Vector3());
  const center = box.getCenter(new THREE.Vector3());
  const radius = Math.max(size.length() / 2, 1e-3);
  const distance = radius / Math.sin(THREE.MathUtils.degToRad(camera.fov / 2)) * 0.9;
  const direction = new THREE.Vector3(-0.8, 0.5, 0.75).normalize();
  camera.position.copy(center).addScaledVector(direction, distance);
  camera.near = distance / 100;
  camera.far = distance * 10;
  camera.updateProjectionMatrix();
  controls.target.copy(center);
  controls.update();
}

function onLoad(gltf) {
  const root = gltf.scene;
  scene.add(root);
  for (const name of ['environment_voxels', 'link_voxels', 'robot']) {
    viewer.groups[name] = root.getObjectByName(name) || null;
  }
  // Voxel boxes have no normals: GLTFLoader shades them flat. Translucent link trees must not
  // hide the robot inside them.
  root.traverse((o) => {
    if (o.isMesh && o.material.transparent) o.material.depthWrite = false;
  });
  const clip = gltf.animations.find((a) => a.name === 'path') || gltf.animations[0];
  if (clip) {
    mixer = new THREE.AnimationMixer(root);
    viewer.clip = clip;
    action = mixer.clipAction(clip);
    action.setLoop(THREE.LoopOnce, 1);
    action.clampWhenFinished = true;
    action.play();
    // Keys are at integer times 0..n-1; the clip lasts n-1 seconds.
    viewer.stateCount = Math.round(clip.duration) + 1;
  } else {
    viewer.stateCount = 1;
  }
  initialState = stateParam === 'last' ? viewer.stateCount - 1
                                       : Math.max(0, parseInt(stateParam, 10) || 0);
  initialState = Math.min(initialState, viewer.stateCount - 1);
  const labels = {
    environment_voxels: 'environment voxels',
    link_voxels: `link voxels (at state ${initialState})`,
    robot: 'robot (collision meshes)',
  };
  for (const [name, label] of Object.entries(labels)) {
    const g = viewer.groups[name];
    if (g && g.children.length + (g.isMesh ? 1 : 0) > 0) addLayerToggle(name, label, firstMaterial(g));
  }

  slider.max = String(viewer.stateCount - 1);
  slider.disabled = viewer.stateCount < 2;
  playButton.disabled = viewer.stateCount < 2;
  document.getElementById('title').textContent = `octomotion: ${modelUrl}`;
  statusLine.textContent = `${viewer.stateCount} path state(s); drag to orbit, scroll to zoom`;
  frame(root);
  setState(initialState);
  viewer.ready = true;
}

function onError(err) {
  viewer.error = String(err && err.message ? err.message : err);
  statusLine.textContent = '';
  document.getElementById('error').textContent =
      `Could not load ${modelUrl}: ${viewer.error}\n(serve this directory over HTTP; see docs/viewer.md)`;
}

slider.addEventListener('input', () => { pause(); setState(Number(slider.value)); });
playButton.addEventListener('click', () => (viewer.playing ? pause() : play()));
window.addEventListener('resize', () => {
  camera.aspect = container.clientWidth / container.clientHeight;
  camera.updateProjectionMatrix();
  renderer.setSize(container.clientWidth, container.clientHeight);
  render();
});

new GLTFLoader().load(modelUrl, onLoad, undefined, onError);
