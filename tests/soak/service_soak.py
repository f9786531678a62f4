#!/usr/bin/env python3
"""Drives a running `sortlast serve` with a few thousand mixed requests (soak test) and
records the server's resident memory after each good frame (the rss_mb of every rank in the frame's
X-Sortlast-Stats header, VmRSS at the end of that frame).

Usage: service_soak.py BASE_URL REQUESTS SAMPLES_OUT.json
Mix, per request i: mostly small frames with a new camera and a new transfer function (PNG and
JPEG), every 7th a bad request (bad JSON, an unknown key, a value out of range: 400), every 11th a
client that sends a request and disconnects without reading the answer, every 13th one that sends
half a request and disconnects. Fails on an unexpected status or a server that stops answering.
"""
import http.client
import json
import math
import socket
import sys
import urllib.parse


def main():
    base, requests, out = sys.argv[1], int(sys.argv[2]), sys.argv[3]
    u = urllib.parse.urlparse(base)
    host, port = u.hostname, u.port
    conn = http.client.HTTPConnection(host, port, timeout=60)
    xs, rss, heap, counts = [], [], [], {"frames": 0, "bad": 0, "dropped": 0, "half": 0, "reconnects": 0}
    bad_bodies = ['{"image.width":', '{"camera.positon":[1,2,3]}', '{"image.width":0}',
                  '{"camera.fov":".nan"}', '[1,2,3]', '{"format":"gif"}',
                  '{"render.method":"magic"}', '{"camera.up":[0,0,0]}']
    # The automatic view of the scene: the orbit below keeps its distance and centre.
    conn.request("POST", "/api/frame", body='{"image.width":48,"image.height":48}',
                 headers={"Content-Type": "application/json"})
    r = conn.getresponse()
    r.read()
    cam = json.loads(r.getheader("X-Sortlast-Stats"))["camera"]
    centre = cam["look_at"]
    radius = math.dist(cam["position"], centre)
    for i in range(requests):
        if i % 11 == 5:  # a client that asks for a frame and leaves without reading the answer
            body = json.dumps({"image.width": 48, "image.height": 48, "camera.fov": 20 + i % 30})
            s = socket.create_connection((host, port), timeout=10)
            s.sendall((f"POST /api/frame HTTP/1.1\r\nHost: {host}\r\nContent-Type: application/json\r\n"
                       f"Content-Length: {len(body)}\r\n\r\n{body}").encode())
            s.close()
            counts["dropped"] += 1
            continue
        if i % 13 == 6:  # half a request, then gone
            s = socket.create_connection((host, port), timeout=10)
            s.sendall(b"POST /api/frame HTTP/1.1\r\nHost: x\r\nContent-Length: 500\r\n\r\n{\"image.wi")
            s.close()
            counts["half"] += 1
            continue
        if i % 7 == 3:
            body, want = bad_bodies[(i // 7) % len(bad_bodies)], 400
        else:
            a = 2 * math.pi * i / 97.0
            req = {"image.width": 48, "image.height": 48,
                   "camera.position": [centre[0] + radius * math.cos(a),
                                        centre[1] + 0.3 * radius * math.sin(a / 3),
                                        centre[2] + radius * math.sin(a)],
                   "camera.look_at": centre,
                   "transfer.points": [[0, 0, 0, 0, 0], [0.3 + 0.2 * (i % 5) / 5, 1, 0.5, 0.2, 0.02 + 0.01 * (i % 4)],
                                       [1, 1, 1, 1, 0.4]],
                   "format": "jpeg" if i % 3 == 0 else "png"}
            body, want = json.dumps(req), 200
        try:
            conn.request("POST", "/api/frame", body=body, headers={"Content-Type": "application/json"})
            r = conn.getresponse()
        except (BrokenPipeError, ConnectionResetError, http.client.RemoteDisconnected):
            # The server closed the kept-alive connection between two requests (allowed by HTTP;
            # a browser reconnects too). Once more on a new connection; failing again is a failure.
            counts["reconnects"] += 1
            print(f"request {i}: the server had closed the connection; reconnecting")
            conn.close()
            conn = http.client.HTTPConnection(host, port, timeout=60)
            conn.request("POST", "/api/frame", body=body, headers={"Content-Type": "application/json"})
            r = conn.getresponse()
        data = r.read()
        if r.status != want:
            print(f"request {i}: status {r.status}, expected {want}: {data[:200]!r}")
            return 1
        if want == 400:
            counts["bad"] += 1
            continue
        counts["frames"] += 1
        stats = json.loads(r.getheader("X-Sortlast-Stats"))
        xs.append(i)
        rss.append(stats["rss_mb"])
        heap.append(stats["heap_mb"])
    json.dump({"x": xs, "rss_mb": rss, "heap_mb": heap}, open(out, "w"))
    if counts["reconnects"] > requests // 100:
        print(f"the server closed {counts['reconnects']} kept-alive connections (over 1 %)")
        return 1
    print("service soak:", requests, "requests:", counts)
    return 0


if __name__ == "__main__":
    sys.exit(main())
