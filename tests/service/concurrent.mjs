// CLIENTS clients at once, half over the WebSocket and half over HTTP (POST /api/frame), each
// with its own camera (around the scene, 360/CLIENTS degrees apart) and ROUNDS requests one after
// another (the WebSocket clients on one connection, a step further each time). Every request must
// be answered 200 with a PNG whose stats report that client's camera; all images must differ.
// Writes OUTDIR/c<i>_<round>.png and .json (the camera asked for), and prints a JSON summary.
// Usage: node concurrent.mjs WS_URL HTTP_BASE OUTDIR [CLIENTS] [SIZE] [ROUNDS]
import crypto from 'node:crypto';
import fs from 'node:fs';
import path from 'node:path';
import WebSocket from 'ws';

const [wsUrl, httpBase, outdir, clientsArg, sizeArg, roundsArg] = process.argv.slice(2);
const clients = Number(clientsArg || 20), size = Number(sizeArg || 128), rounds = Number(roundsArg || 2);
fs.mkdirSync(outdir, { recursive: true });
const problems = [];
setTimeout(() => { console.error('FAIL: not done within 100 s'); process.exit(1); }, 100000);

function camera(i, round) {
  const a = (2 * Math.PI * i) / clients + round * 0.05;
  return [260 * Math.sin(a), 40 + 30 * round, 260 * Math.cos(a)];
}
function request(i, round) {
  return { 'image.width': size, 'image.height': size, 'camera.position': camera(i, round) };
}
function check(i, round, stats, png, latencyMs) {
  const want = camera(i, round);
  const got = stats && stats.camera && stats.camera.position;
  if (!got || got.some((v, k) => Math.abs(v - want[k]) > 1e-6))
    problems.push(`client ${i} round ${round}: stats camera ${JSON.stringify(got)}, asked for ${JSON.stringify(want)}`);
  if (png.subarray(1, 4).toString() !== 'PNG') problems.push(`client ${i} round ${round}: not a PNG`);
  const name = `c${i}_${round}`;
  fs.writeFileSync(path.join(outdir, `${name}.png`), png);
  fs.writeFileSync(path.join(outdir, `${name}.json`), JSON.stringify(request(i, round)));
  return { name, sha: crypto.createHash('sha256').update(png).digest('hex'), latencyMs };
}

async function httpClient(i) {
  const out = [];
  for (let round = 0; round < rounds; round++) {
    const t = Date.now();
    const res = await fetch(`${httpBase}/api/frame`, {
      method: 'POST', headers: { 'Content-Type': 'application/json' }, body: JSON.stringify(request(i, round)),
    });
    const body = Buffer.from(await res.arrayBuffer());
    if (res.status !== 200) { problems.push(`HTTP client ${i} round ${round}: ${res.status} ${body.toString().slice(0, 200)}`); continue; }
    out.push(check(i, round, JSON.parse(res.headers.get('x-sortlast-stats')), body, Date.now() - t));
  }
  return out;
}

function wsClient(i) {
  return new Promise((resolve) => {
    const out = [];
    const ws = new WebSocket(wsUrl);
    let round = 0, header = null, t = 0;
    const send = () => { t = Date.now(); ws.send(JSON.stringify({ id: round, ...request(i, round) })); };
    ws.on('open', send);
    ws.on('error', (e) => { problems.push(`WebSocket client ${i}: ${e.message}`); resolve(out); });
    ws.on('close', () => resolve(out));
    ws.on('message', (data, isBinary) => {
      if (!isBinary) {
        header = JSON.parse(data.toString());
        if (header.id !== round) problems.push(`WebSocket client ${i}: answer for id ${header.id}, waiting for ${round}`);
        if (header.status !== 200) { problems.push(`WebSocket client ${i} round ${round}: ${JSON.stringify(header).slice(0, 200)}`); ws.close(); }
        return;
      }
      out.push(check(i, round, header.stats, data, Date.now() - t));
      if (++round < rounds) send(); else ws.close();
    });
  });
}

const t0 = Date.now();
const all = (await Promise.all(Array.from({ length: clients }, (_, i) => (i % 2 ? httpClient(i) : wsClient(i))))).flat();
const seconds = (Date.now() - t0) / 1000;
if (all.length !== clients * rounds) problems.push(`${all.length} frames for ${clients * rounds} requests`);
const bySha = new Map();
for (const f of all) {
  if (bySha.has(f.sha)) problems.push(`${f.name} and ${bySha.get(f.sha)} are the same image (different cameras)`);
  bySha.set(f.sha, f.name);
}
const lat = all.map((f) => f.latencyMs).sort((a, b) => a - b);
console.log(JSON.stringify({ clients, rounds, frames: all.length, seconds, latency_ms_max: lat[lat.length - 1], latency_ms_median: lat[lat.length >> 1] }));
if (problems.length) { for (const p of problems) console.error(`FAIL: ${p}`); process.exit(1); }
process.exit(0);
