// End-to-end test of the viewer: serves DIR (the output of `octomotion view`) on localhost,
// opens the page in headless Chromium (playwright-core, Debian's /usr/bin/chromium, software
// WebGL), reads the canvas pixels and checks that the environment voxels (blue) and the robot
// (orange) are drawn where their bounding boxes project, and that stepping the path moves the
// robot. Optionally saves a screenshot.
//
//   node viewer/test/e2e.mjs --dir DIR --model NAME.glb [--state I|last] [--screenshot FILE.png]
//                            [--page /viewer/]   (the page's path under DIR; default /)
//
// Exit status: 0 pass, 1 a check failed, 2 could not run (prints why).
import http from 'node:http';
import fs from 'node:fs';
import path from 'node:path';
import os from 'node:os';

function parseArgs(argv) {
  const a = { dir: null, page: '/', model: 'scene.glb', state: 0, screenshot: null, width: 1024, height: 700,
              linkVoxels: true };
  for (let i = 2; i < argv.length; ++i) {
    const v = () => {
      if (i + 1 >= argv.length) throw new Error(`${argv[i]}: missing value`);
      return argv[++i];
    };
    switch (argv[i]) {
      case '--dir': a.dir = v(); break;
      case '--model': a.model = v(); break;
      case '--page': a.page = v(); break;
      case '--state': { const s = v(); a.state = s === 'last' ? 'last' : Number(s); break; }
      case '--screenshot': a.screenshot = v(); break;
      case '--width': a.width = Number(v()); break;
      case '--height': a.height = Number(v()); break;
      case '--no-link-voxels-in-screenshot': a.linkVoxels = false; break;
      default: throw new Error(`unknown argument ${argv[i]}`);
    }
  }
  if (!a.dir) throw new Error('--dir is required');
  return a;
}

const types = { '.html': 'text/html', '.js': 'text/javascript', '.mjs': 'text/javascript',
                '.glb': 'model/gltf-binary', '.json': 'application/json', '.png': 'image/png' };

function serve(root) {
  const server = http.createServer((req, res) => {
    const url = new URL(req.url, 'http://localhost');
    let file = path.normalize(path.join(root, decodeURIComponent(url.pathname)));
    if (!file.startsWith(path.resolve(root))) { res.writeHead(403); res.end(); return; }
    if (file.endsWith(path.sep)) file = path.join(file, 'index.html');
    fs.readFile(file, (err, data) => {
      if (err) { res.writeHead(404); res.end('not found'); return; }
      res.writeHead(200, { 'Content-Type': types[path.extname(file)] || 'application/octet-stream' });
      res.end(data);
    });
  });
  return new Promise((resolve) => server.listen(0, '127.0.0.1', () => resolve(server)));
}

// Runs in the page: hides/shows layers, renders, classifies the canvas pixels by colour and
// projects the groups' bounding boxes to pixel rectangles.
function measure({ showLinkVoxels }) {
  const v = window.octomotionViewer;
  if (v.groups.link_voxels) v.groups.link_voxels.visible = showLinkVoxels;
  v.render();
  const canvas = v.renderer.domElement;
  const w = canvas.width, h = canvas.height;
  const copy = document.createElement('canvas');
  copy.width = w; copy.height = h;
  const ctx = copy.getContext('2d');
  ctx.drawImage(canvas, 0, 0);
  const px = ctx.getImageData(0, 0, w, h).data;

  // Pixel rectangle of an object's world bounding box (all 8 corners projected).
  const rect = (object) => {
    if (!object) return null;
    object.updateWorldMatrix(true, true);
    let lo = null, hi = null;
    object.traverse((o) => {
      if (!o.isMesh) return;
      o.geometry.computeBoundingBox();
      const b = o.geometry.boundingBox;
      for (let c = 0; c < 8; ++c) {
        const p = b.min.clone();
        if (c & 1) p.x = b.max.x;
        if (c & 2) p.y = b.max.y;
        if (c & 4) p.z = b.max.z;
        p.applyMatrix4(o.matrixWorld).project(v.camera);
        const x = (p.x + 1) / 2 * w, y = (1 - p.y) / 2 * h;
        lo = lo ? [Math.min(lo[0], x), Math.min(lo[1], y)] : [x, y];
        hi = hi ? [Math.max(hi[0], x), Math.max(hi[1], y)] : [x, y];
      }
    });
    return lo ? { x0: lo[0] - 2, y0: lo[1] - 2, x1: hi[0] + 2, y1: hi[1] + 2 } : null;
  };
  const envRect = rect(v.groups.environment_voxels);
  const robotRect = rect(v.groups.robot);
  const inside = (r, x, y) => r && x >= r.x0 && x <= r.x1 && y >= r.y0 && y <= r.y1;

  const stats = { width: w, height: h, background: 0, blue: 0, blueInside: 0, orange: 0,
                  orangeInside: 0, other: 0, orangeCx: 0, orangeCy: 0, envRect, robotRect };
  for (let y = 0; y < h; ++y) {
    for (let x = 0; x < w; ++x) {
      const i = 4 * (y * w + x);
      const r = px[i], g = px[i + 1], b = px[i + 2];
      const spread = Math.max(r, g, b) - Math.min(r, g, b);
      if (spread < 24) { stats.background += 1; continue; }  // greys: background, panel
      // Canvas rows are read top-down, like the rectangles.
      if (b > r + 50 && b >= g) {
        stats.blue += 1;
        if (inside(envRect, x, y)) stats.blueInside += 1;
      } else if (r > b + 80 && r >= g) {
        stats.orange += 1;
        stats.orangeCx += x; stats.orangeCy += y;
        if (inside(robotRect, x, y)) stats.orangeInside += 1;
      } else {
        stats.other += 1;
      }
    }
  }
  if (stats.orange) { stats.orangeCx /= stats.orange; stats.orangeCy /= stats.orange; }
  return stats;
}

// Runs in the page: after setState(s), every animated link node sits at key s of its track
// (the slider shows exactly the path's states, the last one included).
function checkKeys(s) {
  const v = window.octomotionViewer;
  v.setState(s);
  let worst = 0, tracks = 0;
  for (const track of v.clip.tracks) {
    if (!track.name.endsWith('.position')) continue;
    const node = v.scene.getObjectByName(track.name.slice(0, -'.position'.length));
    if (!node) return { error: `no node for track ${track.name}` };
    for (let k = 0; k < 3; ++k) {
      worst = Math.max(worst, Math.abs(node.position.getComponent(k) - track.values[3 * s + k]));
    }
    ++tracks;
  }
  return { worst, tracks };
}

async function main() {
  const a = parseArgs(process.argv);
  const executablePath = process.env.CHROMIUM || '/usr/bin/chromium';
  if (!fs.existsSync(executablePath)) {
    console.log(`SKIP: no Chromium at ${executablePath} (apt-get install chromium)`);
    process.exit(2);
  }
  let chromium;
  try {
    ({ chromium } = await import('playwright-core'));
  } catch (e) {
    console.log('SKIP: playwright-core is not installed (npm ci --prefix viewer)');
    process.exit(2);
  }
  const server = await serve(path.resolve(a.dir));
  const port = server.address().port;
  const userDataDir = fs.mkdtempSync(path.join(os.tmpdir(), 'octomotion-chromium-'));
  // The flags that work on this machine's closed network (no background connections), plus
  // SwiftShader for WebGL without a GPU.
  const context = await chromium.launchPersistentContext(userDataDir, {
    executablePath,
    headless: true,
    viewport: { width: a.width, height: a.height },
    args: ['--no-sandbox', '--disable-gpu', '--disable-quic', '--no-first-run',
           '--disable-background-networking', '--disable-component-update', '--disable-sync',
           '--use-angle=swiftshader', '--enable-unsafe-swiftshader', '--ignore-gpu-blocklist'],
  });
  const failures = [];
  const logs = [];
  let result = {};
  try {
    const page = await context.newPage();
    page.on('console', (m) => logs.push(`console.${m.type()}: ${m.text()}`));
    page.on('pageerror', (e) => logs.push(`pageerror: ${e.message}`));
    const url = `http://127.0.0.1:${port}${a.page}?model=${encodeURIComponent(a.model)}&state=${a.state}`;
    await page.goto(url);
    await page.waitForFunction(
        () => window.octomotionViewer && (window.octomotionViewer.ready || window.octomotionViewer.error),
        null, { timeout: 40000 });
    const error = await page.evaluate(() => window.octomotionViewer.error);
    if (error) throw new Error(`the viewer could not load the model: ${error}`);
    const stateCount = await page.evaluate(() => window.octomotionViewer.stateCount);
    if (a.state === 'last') {
      a.state = stateCount - 1;
      await page.evaluate((s) => window.octomotionViewer.setState(s), a.state);
    }

    // 1. Robot and environment at the chosen state, link voxels hidden (they enclose the robot).
    const first = await page.evaluate(measure, { showLinkVoxels: false });
    const pixels = first.width * first.height;
    result = { url, stateCount, first };
    if (first.blue < 0.002 * pixels) failures.push(`too few environment (blue) pixels: ${first.blue}`);
    if (first.blue && first.blueInside < 0.95 * first.blue) {
      failures.push(`environment pixels outside the environment's box: ${first.blue - first.blueInside}`);
    }
    if (first.orange < 0.0005 * pixels) failures.push(`too few robot (orange) pixels: ${first.orange}`);
    if (first.orange && first.orangeInside < 0.95 * first.orange) {
      failures.push(`robot pixels outside the robot's box: ${first.orange - first.orangeInside}`);
    }
    // 2. Another path state (the first, or the last when the first is shown): the robot moved.
    if (stateCount > 1) {
      const other = a.state === 0 ? stateCount - 1 : 0;
      result.otherState = other;
      await page.evaluate((s) => window.octomotionViewer.setState(s), other);
      const last = await page.evaluate(measure, { showLinkVoxels: false });
      result.last = last;
      const moved = Math.hypot(last.orangeCx - first.orangeCx, last.orangeCy - first.orangeCy);
      result.robotMovedPixels = moved;
      if (last.orange < 0.0005 * pixels) failures.push(`no robot at state ${other}: ${last.orange}`);
      if (!(moved > 3)) failures.push(`the robot did not move along the path (${moved} px)`);
      await page.evaluate((s) => window.octomotionViewer.setState(s), a.state);
    }
    // 3. The slider's states are the path's states (first, chosen, last).
    for (const s of new Set([0, a.state, stateCount - 1])) {
      const k = await page.evaluate(checkKeys, s);
      result[`keysAtState${s}`] = k;
      if (k.error || !(k.tracks > 0) || !(k.worst < 1e-5)) {
        failures.push(`state ${s}: link nodes not at the path's keys: ${JSON.stringify(k)}`);
      }
    }
    await page.evaluate((s) => window.octomotionViewer.setState(s), a.state);
    // 4. With the link voxels shown (as a user sees it first): more coloured pixels.
    const withLinks = await page.evaluate(measure, { showLinkVoxels: true });
    result.withLinkVoxels = { other: withLinks.other, orange: withLinks.orange };
    if (a.screenshot) {
      if (!a.linkVoxels) await page.evaluate(() => window.octomotionViewer.setVisible('link_voxels', false));
      fs.mkdirSync(path.dirname(path.resolve(a.screenshot)), { recursive: true });
      await page.screenshot({ path: a.screenshot });
      result.screenshot = a.screenshot;
    }
  } catch (e) {
    failures.push(String(e && e.message ? e.message : e));
  } finally {
    await context.close();
    server.close();
    fs.rmSync(userDataDir, { recursive: true, force: true });
  }
  console.log(JSON.stringify(result, null, 1));
  if (failures.length) {
    for (const l of logs) console.log(l);
    for (const f of failures) console.log(`FAIL: ${f}`);
    process.exit(1);
  }
  console.log('PASS');
}

main().catch((e) => {
  console.log(`ERROR: ${e && e.stack ? e.stack : e}`);
  process.exit(2);
});
