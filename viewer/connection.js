// Frame requests to `sortlast serve`: over the WebSocket /api/stream (falling back to
// POST /api/frame when the socket cannot be opened), latest state wins, at most maxInFlight
// requests outstanding. submit() never waits: it replaces the state waiting to be sent, which
// goes out as soon as a reply (or drop) for an older request arrives.

export class FrameClient {
  // onFrame(meta, blob, stats), onError(meta, message), onStatus(text, isError),
  // onReconnect(): the socket is open again (send the current state).
  constructor({ token = '', maxInFlight = 2, onFrame, onError, onStatus, onReconnect }) {
    this.token = token;
    this.maxInFlight = maxInFlight;
    this.onFrame = onFrame;
    this.onError = onError;
    this.onStatus = onStatus || (() => {});
    this.onReconnect = onReconnect || (() => {});
    this.pending = null;          // {request, meta} not yet sent
    this.inflight = new Map();    // id -> meta
    this.nextId = 1;
    this.ws = null;
    this.wsOpen = false;
    this.everOpened = false;
    this.useHttp = false;
    this.header = null;           // the text reply whose image is the next binary message
    this.retryMs = 500;
    this.closed = false;
    setInterval(() => this.#expire(), 5000);
  }

  get transport() { return this.useHttp ? 'http' : this.wsOpen ? 'websocket' : 'connecting'; }
  get busy() { return this.inflight.size > 0 || this.pending !== null; }

  url(path, ws = false) {
    const q = this.token ? `?token=${encodeURIComponent(this.token)}` : '';
    if (!ws) return `${path}${q}`;
    const proto = location.protocol === 'https:' ? 'wss:' : 'ws:';
    return `${proto}//${location.host}${path}${q}`;
  }

  connect() {
    if (this.useHttp || this.closed) return;
    let ws;
    try {
      ws = new WebSocket(this.url('/api/stream', true));
    } catch (e) {
      this.#fallback(`WebSocket unavailable (${e.message})`);
      return;
    }
    ws.binaryType = 'arraybuffer';
    this.ws = ws;
    ws.onopen = () => {
      const again = this.everOpened;
      this.wsOpen = true;
      this.everOpened = true;
      this.retryMs = 500;
      this.onStatus(null);
      if (again) this.onReconnect();
      this.#pump();
    };
    ws.onmessage = (ev) => this.#message(ev.data);
    ws.onclose = () => {
      const wasOpen = this.wsOpen;
      this.wsOpen = false;
      this.ws = null;
      this.header = null;
      this.inflight.clear();
      if (!this.everOpened) { this.#fallback('WebSocket /api/stream could not be opened'); return; }
      if (this.closed) return;
      if (wasOpen) this.onStatus('Connection to the server lost; reconnecting…', true);
      setTimeout(() => this.connect(), this.retryMs);
      this.retryMs = Math.min(this.retryMs * 2, 5000);
    };
  }

  submit(request, meta) {
    this.pending = { request, meta };
    this.#pump();
  }

  #fallback(why) {
    this.useHttp = true;
    this.onStatus(`${why}; using HTTP requests instead`, false);
    setTimeout(() => this.onStatus(null), 4000);
    this.#pump();
  }

  #pump() {
    while (this.pending && this.inflight.size < this.maxInFlight) {
      if (!this.useHttp && !this.wsOpen) return;
      const { request, meta } = this.pending;
      this.pending = null;
      const id = this.nextId++;
      meta.id = id;
      meta.t0 = performance.now();
      this.inflight.set(id, meta);
      if (this.useHttp) this.#http(id, request, meta);
      else this.ws.send(JSON.stringify({ id, ...request }));
    }
  }

  #finish(id) {
    this.inflight.delete(id);
    this.#pump();
  }

  #message(data) {
    if (typeof data === 'string') {
      let msg;
      try { msg = JSON.parse(data); } catch { this.onStatus('The server sent a malformed reply', true); return; }
      const meta = this.inflight.get(msg.id);
      if (msg.dropped) { this.#finish(msg.id); return; }
      if (msg.status === 200) { this.header = msg; return; }
      if (meta) this.onError(meta, msg.error || `error ${msg.status}`);
      else this.onStatus(msg.error || `error ${msg.status}`, true);
      this.#finish(msg.id);
      return;
    }
    const header = this.header;
    this.header = null;
    if (!header) return;
    const meta = this.inflight.get(header.id);
    if (meta) this.onFrame(meta, new Blob([data], { type: header.content_type || 'image/png' }), header.stats || {});
    this.#finish(header.id);
  }

  async #http(id, request, meta) {
    try {
      const res = await fetch(this.url('/api/frame'), {
        method: 'POST', headers: { 'Content-Type': 'application/json' }, body: JSON.stringify(request),
      });
      if (!res.ok) {
        let msg = `HTTP ${res.status}`;
        try { msg = (await res.json()).error || msg; } catch { /* not JSON */ }
        this.onError(meta, msg);
      } else {
        let stats = {};
        try { stats = JSON.parse(res.headers.get('X-Sortlast-Stats') || '{}'); } catch { /* none */ }
        const blob = await res.blob();
        this.onFrame(meta, blob, stats);
      }
    } catch (e) {
      this.onError(meta, `Request failed: ${e.message}`);
    }
    this.#finish(id);
  }

  // A request with no answer for 2 minutes is given up, so the queue never stalls.
  #expire() {
    const now = performance.now();
    for (const [id, meta] of this.inflight) {
      if (now - meta.t0 > 120000) { this.onError(meta, 'The server did not answer a frame request'); this.#finish(id); }
    }
  }
}
