// A slow reader and clients that leave mid-frame do not stall the others. While
//   - "slow": a WebSocket that asks for a large frame (SLOW_SIZE^2 PNG) every 200 ms and never
//     reads (its socket paused), and
//   - "quitters": WebSockets and HTTP requests that ask for a 768^2 frame and go away 100 ms later
//     (closed / aborted mid-frame), one every 300 ms,
// are at it, a "good" WebSocket client renders GOOD frames one after another at 256^2: each must
// come within BOUND_S seconds and all of them; GET /api/health must answer within 2 s meanwhile.
// Writes OUTDIR/good_last.png and good_last.json (the request) and prints a JSON summary.
// Usage: node slow_client.mjs WS_URL HTTP_BASE OUTDIR [SLOW_SIZE] [GOOD] [BOUND_S]
import fs from 'node:fs';
import path from 'node:path';
import WebSocket from 'ws';

const [wsUrl, httpBase, outdir, slowSizeArg, goodArg, boundArg] = process.argv.slice(2);
const slowSize = Number(slowSizeArg || 1024), goodCount = Number(goodArg || 15), boundS = Number(boundArg || 10);
fs.mkdirSync(outdir, { recursive: true });
const problems = [];
const fail = (m) => { console.error(`FAIL: ${m}`); process.exit(1); };
setTimeout(() => fail('not done within 110 s'), 110000);
const sleep = (ms) => new Promise((r) => setTimeout(r, ms));
let stop = false;

// The slow reader.
const slow = new WebSocket(wsUrl);
let slowSent = 0;
slow.on('error', () => {});
slow.on('open', async () => {
  slow.pause();  // never reads: the service's writes to it back up
  for (let id = 1; !stop && id <= 200; id++) {
    slow.send(JSON.stringify({ id, 'image.width': slowSize, 'image.height': slowSize,
      'camera.position': [300 * Math.sin(id / 10), 100, 300 * Math.cos(id / 10)] }));
    slowSent++;
    await sleep(200);
  }
});

// Clients that leave mid-frame.
let quitters = 0;
async function quitters_loop() {
  for (let i = 0; !stop && i < 100; i++) {
    const req = { 'image.width': 768, 'image.height': 768, 'camera.position': [200, 50 + i, 250] };
    if (i % 2 === 0) {
      const ws = new WebSocket(wsUrl);
      ws.on('error', () => {});
      ws.on('open', () => { ws.send(JSON.stringify({ id: i, ...req })); setTimeout(() => ws.terminate(), 100); });
    } else {
      const ac = new AbortController();
      setTimeout(() => ac.abort(), 100);
      fetch(`${httpBase}/api/frame`, { method: 'POST', body: JSON.stringify(req), signal: ac.signal }).catch(() => {});
    }
    quitters++;
    await sleep(300);
  }
}

// Health checks while all this goes on.
const healthMs = [];
async function health_loop() {
  while (!stop) {
    const t = Date.now();
    try {
      const ac = new AbortController();
      const timer = setTimeout(() => ac.abort(), 5000);
      const res = await fetch(`${httpBase}/api/health`, { signal: ac.signal });
      clearTimeout(timer);
      await res.json();
      healthMs.push(Date.now() - t);
    } catch (e) { problems.push(`GET /api/health: ${e.message}`); }
    await sleep(500);
  }
}

// The good client.
function good() {
  return new Promise((resolve) => {
    const ws = new WebSocket(wsUrl);
    const lat = [];
    let n = 0, t = 0, header = null, req = null;
    const send = () => {
      req = { id: n, 'image.width': 256, 'image.height': 256, 'camera.position': [250 * Math.sin(n / 5), -60, 250 * Math.cos(n / 5)] };
      t = Date.now();
      ws.send(JSON.stringify(req));
    };
    const guard = setInterval(() => {
      if (t && Date.now() - t > boundS * 1000) { problems.push(`good client: frame ${n} not there within ${boundS} s`); clearInterval(guard); ws.terminate(); }
    }, 100);
    ws.on('open', () => setTimeout(send, 1000));  // let the slow client's queue build up first
    ws.on('error', (e) => problems.push(`good client: ${e.message}`));
    ws.on('close', () => { clearInterval(guard); resolve(lat); });
    ws.on('message', (data, isBinary) => {
      if (!isBinary) {
        header = JSON.parse(data.toString());
        if (header.status !== 200) { problems.push(`good client: ${JSON.stringify(header).slice(0, 200)}`); ws.close(); }
        return;
      }
      lat.push(Date.now() - t);
      if (n === goodCount - 1) {
        fs.writeFileSync(path.join(outdir, 'good_last.png'), data);
        fs.writeFileSync(path.join(outdir, 'good_last.json'), JSON.stringify(Object.fromEntries(Object.entries(req).filter(([k]) => k !== 'id'))));
      }
      if (++n < goodCount) send(); else ws.close();
    });
  });
}

const t0 = Date.now();
const healthDone = health_loop();
const quittersDone = quitters_loop();
const lat = await good();
stop = true;
await Promise.all([healthDone, quittersDone]);
const seconds = (Date.now() - t0) / 1000;
if (lat.length !== goodCount) problems.push(`good client: ${lat.length} of ${goodCount} frames`);
const sorted = [...lat].sort((a, b) => a - b);
const hs = [...healthMs].sort((a, b) => a - b);
if (hs.length && hs[hs.length - 1] > 2000) problems.push(`GET /api/health took ${hs[hs.length - 1]} ms`);
console.log(JSON.stringify({ good_frames: lat.length, good_latency_ms_median: sorted[sorted.length >> 1], good_latency_ms_max: sorted[sorted.length - 1],
  slow_requests_sent: slowSent, quitters, health_ms_max: hs[hs.length - 1], seconds }));
slow.terminate();
if (problems.length) { for (const p of problems) console.error(`FAIL: ${p}`); process.exit(1); }
process.exit(0);
