// Latest wins: one WebSocket connection sends COUNT frame requests back to back (a camera orbiting
// a degree per request) at SIZE x SIZE, ROUNDS times. Every id must be answered exactly once,
// either {"id", "dropped": true} or a 200 header followed by the image; at least one request per
// run must have been dropped; images arrive in increasing id order; the last id of every round gets
// an image. Writes OUTDIR/last.png and OUTDIR/last.json (its header, for the shell to render the
// same camera) and prints a summary line of JSON.
// Usage: node latest_wins.mjs WS_URL OUTDIR [COUNT] [SIZE] [ROUNDS]
import fs from 'node:fs';
import path from 'node:path';
import WebSocket from 'ws';

const [url, outdir, countArg, sizeArg, roundsArg] = process.argv.slice(2);
const count = Number(countArg || 30), size = Number(sizeArg || 512), rounds = Number(roundsArg || 3);
fs.mkdirSync(outdir, { recursive: true });
const fail = (msg) => { console.error(`FAIL: ${msg}`); process.exit(1); };
setTimeout(() => fail('not done within 90 s'), 90000);

const ws = new WebSocket(url);
ws.on('error', (e) => fail(`WebSocket error: ${e.message}`));
ws.on('close', () => { if (!finished) fail('the service closed the connection'); });
let finished = false;
const answers = new Map();  // id -> 'dropped' | 'image' | 'error'
const imageOrder = [];
let pending = null;         // a 200 header waiting for its image
let round = 0, dropped = 0, images = 0;
const t0 = Date.now();
const roundTimes = [];

function camera(id) {
  const a = (id * Math.PI) / 180, r = 250;
  return [r * Math.sin(a), 80, r * Math.cos(a)];
}
function sendRound() {
  const first = round * count + 1;
  for (let id = first; id < first + count; id++)
    ws.send(JSON.stringify({ id, 'image.width': size, 'image.height': size, 'camera.position': camera(id) }));
  roundTimes.push(Date.now());
}
ws.on('open', sendRound);
ws.on('message', (data, isBinary) => {
  if (isBinary) {
    if (!pending) fail('an image without a header');
    const id = pending.id;
    answers.set(id, 'image');
    imageOrder.push(id);
    images++;
    const last = (round + 1) * count;
    if (id === last) {
      fs.writeFileSync(path.join(outdir, 'last.png'), data);
      fs.writeFileSync(path.join(outdir, 'last.json'), JSON.stringify(pending));
      roundTimes[round] = Date.now() - roundTimes[round];
      round++;
      pending = null;
      if (round < rounds) sendRound(); else setTimeout(finish, 500);  // any stray message after?
    }
    pending = null;
    return;
  }
  const h = JSON.parse(data.toString());
  if (answers.has(h.id)) fail(`id ${h.id} answered twice`);
  if (h.dropped === true) { answers.set(h.id, 'dropped'); dropped++; return; }
  if (h.status !== 200) fail(`id ${h.id}: status ${h.status} ${h.error || ''}`);
  if (pending) fail(`header for id ${h.id} before the image of id ${pending.id}`);
  pending = h;
});
function finish() {
  finished = true;
  const total = rounds * count;
  for (let id = 1; id <= total; id++) if (!answers.has(id)) fail(`id ${id} was never answered`);
  if (answers.size !== total) fail(`${answers.size} answers to ${total} requests`);
  for (let i = 1; i < imageOrder.length; i++)
    if (imageOrder[i] <= imageOrder[i - 1]) fail(`image of id ${imageOrder[i]} after id ${imageOrder[i - 1]}`);
  for (let r = 1; r <= rounds; r++) if (answers.get(r * count) !== 'image') fail(`the last id of round ${r} got no image`);
  if (dropped === 0) fail(`none of ${total} requests sent back to back was dropped`);
  console.log(JSON.stringify({ requests: total, dropped, images, round_ms: roundTimes, seconds: (Date.now() - t0) / 1000 }));
  ws.close();
  process.exit(0);
}
