#!/usr/bin/env python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""dform studio under greedy clients (docs/benchmarks.md, "Studio under load"):

1. a normal request with the token (POST /api/session) while 200 connections without the token
   stay half-open (each sends half a request line and nothing more, reopened as the server drops
   them) and 64 event streams are open: its time, median and worst of 30;
2. a 100 MB chunked upload with the token: its answer (413) and the server's RSS growth, at its
   peak while the body arrives and after;
3. four exports at resolution 1000 abandoned by their clients 3 s after they were asked for: the
   server's RSS 10 s after the clients went, against its figure before they came.

    studio_budget.py BUILD/dform

Prints one line per figure; exits 1 when a figure is over its bar (1 s; 20 MB; 100 MB).
"""
import json
import os
import re
import socket
import statistics
import subprocess
import sys
import threading
import time

HALF_OPEN, STREAMS, REQUESTS = 200, 64, 30
CHUNKED_MB = 100
EXPORTS, EXPORT_RESOLUTION, ABANDON_AFTER, SETTLE = 4, 1000, 3.0, 10.0


def rss_mb(pid):
    with open(f"/proc/{pid}/status") as f:
        for line in f:
            if line.startswith("VmRSS:"):
                return int(line.split()[1]) / 1024
    return float("nan")


class Studio:
    def __init__(self, dform):
        self.process = subprocess.Popen([dform, "studio", "--no-browser", "--port", "0"],
                                        stdout=subprocess.PIPE, stderr=subprocess.DEVNULL, text=True)
        line = self.process.stdout.readline()
        found = re.search(r"http://127\.0\.0\.1:(\d+)/\?token=([0-9a-f]+)", line)
        if not found:
            raise SystemExit(f"no address printed: {line!r}")
        self.port, self.token = int(found.group(1)), found.group(2)
        self.host = f"127.0.0.1:{self.port}"

    def request(self, method, path, body=b"", timeout=600):
        """One request on a connection of its own: (status, body, seconds)."""
        started = time.monotonic()
        s = socket.create_connection(("127.0.0.1", self.port), timeout=timeout)
        head = (f"{method} {path} HTTP/1.1\r\nHost: {self.host}\r\nX-Dform-Token: {self.token}\r\n"
                f"Content-Type: application/json\r\nContent-Length: {len(body)}\r\n"
                "Connection: close\r\n\r\n").encode()
        s.sendall(head + body)
        answer = b""
        while True:
            chunk = s.recv(65536)
            if not chunk:
                break
            answer += chunk
        s.close()
        status = int(answer.split(b" ", 2)[1]) if answer else 0
        return status, answer.split(b"\r\n\r\n", 1)[-1], time.monotonic() - started

    def session(self):
        status, body, _ = self.request("POST", "/api/session", b"{}")
        assert status == 200, status
        return json.loads(body)["session"]

    def stop(self):
        self.process.terminate()
        self.process.wait()


def half_open(studio, count, stop):
    """Keeps `count` connections open that never finish their request line."""
    sockets = []
    while not stop.is_set():
        alive = []
        for s in sockets:
            try:
                if s.recv(1, socket.MSG_DONTWAIT | socket.MSG_PEEK) == b"":
                    s.close()
                    continue
            except BlockingIOError:
                pass
            except OSError:
                s.close()
                continue
            alive.append(s)
        sockets = alive
        while len(sockets) < count:
            s = socket.create_connection(("127.0.0.1", studio.port))
            s.sendall(b"POST /api/sess")
            sockets.append(s)
        time.sleep(0.1)
    for s in sockets:
        s.close()


def under_load(studio):
    session = studio.session()
    streams = []
    for _ in range(STREAMS):
        s = socket.create_connection(("127.0.0.1", studio.port))
        s.sendall(f"GET /api/events?session={session}&token={studio.token} HTTP/1.1\r\n"
                  f"Host: {studio.host}\r\n\r\n".encode())
        s.settimeout(30)
        assert b"text/event-stream" in s.recv(4096)
        streams.append(s)
    stop = threading.Event()
    attacker = threading.Thread(target=half_open, args=(studio, HALF_OPEN, stop))
    attacker.start()
    time.sleep(1.0)  # every half-open connection is in place
    times = []
    for _ in range(REQUESTS):
        status, _, seconds = studio.request("POST", "/api/session", b"{}")
        assert status == 200, status
        times.append(seconds)
        time.sleep(0.05)
    stop.set()
    attacker.join()
    for s in streams:
        s.close()
    median, worst = statistics.median(times), max(times)
    print(f"token request under {HALF_OPEN} half-open connections and {STREAMS} event streams: "
          f"median {1000 * median:.1f} ms, worst {1000 * worst:.1f} ms of {REQUESTS} (bar 1000 ms)")
    return worst <= 1.0


def chunked_upload(studio):
    session = studio.session()
    before = rss_mb(studio.process.pid)
    peak = [before]
    done = threading.Event()

    def sample():
        while not done.is_set():
            peak[0] = max(peak[0], rss_mb(studio.process.pid))
            time.sleep(0.01)

    sampler = threading.Thread(target=sample)
    sampler.start()
    s = socket.create_connection(("127.0.0.1", studio.port), timeout=60)
    s.sendall((f"POST /api/outline HTTP/1.1\r\nHost: {studio.host}\r\nX-Dform-Token: {studio.token}\r\n"
               "Content-Type: application/json\r\nTransfer-Encoding: chunked\r\n\r\n").encode())
    prefix = json.dumps({"session": session, "piece": "a", "name": "big.json", "text": ""})[:-2]
    chunk = b"%x\r\n%s\r\n" % (1 << 20, b" " * (1 << 20))
    sent = 0
    try:
        s.sendall(b"%x\r\n%s\r\n" % (len(prefix), prefix.encode()))
        for _ in range(CHUNKED_MB):
            s.sendall(chunk)
            sent += 1
        s.sendall(b"0\r\n\r\n")
    except OSError:
        pass  # the server closed the connection once the body passed its limit
    answer = b""
    try:
        while True:
            part = s.recv(65536)
            if not part:
                break
            answer += part
    except OSError:
        pass
    s.close()
    time.sleep(1.0)
    after = rss_mb(studio.process.pid)
    done.set()
    sampler.join()
    status = answer.split(b" ", 2)[1].decode() if answer else "none"
    print(f"{CHUNKED_MB} MB chunked upload: answered {status} after {sent} MB sent; RSS "
          f"{before:.1f} MB before, peak +{peak[0] - before:.1f} MB, +{after - before:.1f} MB after "
          f"(bar 20 MB)")
    return status == "413" and peak[0] - before <= 20


def abandoned_exports(studio):
    sessions = [studio.session() for _ in range(EXPORTS)]
    time.sleep(1.0)
    idle = rss_mb(studio.process.pid)
    clients = []
    for session in sessions:
        body = json.dumps({"session": session, "resolution": EXPORT_RESOLUTION,
                           "profile": "laser"}).encode()
        s = socket.create_connection(("127.0.0.1", studio.port))
        s.sendall((f"POST /api/export HTTP/1.1\r\nHost: {studio.host}\r\nX-Dform-Token: {studio.token}\r\n"
                   f"Content-Type: application/json\r\nContent-Length: {len(body)}\r\n\r\n").encode() + body)
        clients.append(s)
    time.sleep(ABANDON_AFTER)
    busy = rss_mb(studio.process.pid)
    for s in clients:
        s.close()
    gone = time.monotonic()
    time.sleep(SETTLE)
    settled = rss_mb(studio.process.pid)
    print(f"{EXPORTS} exports at resolution {EXPORT_RESOLUTION} abandoned after {ABANDON_AFTER:.0f} s: "
          f"RSS {idle:.1f} MB idle, {busy:.1f} MB as they ran, {settled:.1f} MB "
          f"{time.monotonic() - gone:.0f} s after the clients went (+{settled - idle:.1f} MB; bar 100 MB)")
    return settled - idle <= 100


def main():
    studio = Studio(sys.argv[1])
    try:
        ok = [under_load(studio), chunked_upload(studio), abandoned_exports(studio)]
    finally:
        studio.stop()
    print(f"load average {os.getloadavg()[0]:.1f} on {os.cpu_count()} cores")
    return 0 if all(ok) else 1


if __name__ == "__main__":
    sys.exit(main())
