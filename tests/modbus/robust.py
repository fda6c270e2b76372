#!/usr/bin/env python3
"""The Modbus server under load it must survive (README "Modbus TCP",
contracts.md sec. 6): pipelined requests, full slots, idle connections, a
machine whose stdout nobody reads, a tooth search that computes for
seconds, read-only and allow-listed servers.  Every wait has a limit; a
round trip over 150 ms fails.  Clients come from several loopback
addresses (127.0.0.0/8 is all loopback on Linux), because one address may
hold at most MAX-1 of the MAX slots.

  robust.py pipeline PORT               (s42 run loop.kp --modbus, idle)
  robust.py slots PORT MAX              (--modbus-max-clients MAX)
  robust.py busy PORT                   (the default 8 slots: seven busy clients, a loop of newcomers, a poller)
  robust.py full PORT MAX               (--modbus-max-clients MAX: every slot active, a newcomer refused)
  robust.py perhost PORT MAX            (--modbus-max-clients MAX: one address holds at most MAX-1)
  robust.py idle PORT SECONDS           (--modbus-idle SECONDS)
  robust.py readonly PORT               (--modbus-read-only)
  robust.py refused PORT                (--modbus-allow without 127.0.0.1)
  robust.py probe PORT SECONDS          (round trips of a running server)
  robust.py tuisearch PORT              (s42 tui endmill_search.kp with a big tool: Пуск, Пуск, the search)
  robust.py stall S42 PROGRAM           (starts s42 itself: --trace=json into a pipe nobody reads)
  robust.py search S42 PROGRAM ARGS...  (starts s42 itself: a long tooth search)
"""
import os
import socket
import struct
import subprocess
import sys
import threading
import time

LIMIT_MS = 150.0
fails = []
passes = 0
worst = 0.0
tid = 0


def check(ok, what):
    global passes
    if ok:
        passes += 1
    else:
        fails.append(what)
    return ok


GRACE = 1.0   # s: a connection accepted or asking this recently is never closed for a newcomer


def connect(port, timeout=3, src=None):
    """A connection from 127.0.0.1, or from the loopback address src."""
    s = socket.create_connection(("127.0.0.1", port), timeout=timeout,
                                 source_address=(src, 0) if src else None)
    s.setsockopt(socket.IPPROTO_TCP, socket.TCP_NODELAY, 1)
    return s


def frame(pdu, t=None):
    global tid
    if t is None:
        tid = (tid + 1) & 0xFFFF
        t = tid
    return struct.pack(">HHHB", t, 0, len(pdu) + 1, 1) + pdu


def read_ir(a, n):
    return struct.pack(">BHH", 4, a, n)


def recv_frames(s, count, timeout=2.0):
    """Up to `count` reply frames; fewer when the time runs out or the
    server closes.  Returns (frames, closed)."""
    s.settimeout(0.05)
    buf = b""
    out = []
    end = time.monotonic() + timeout
    closed = False
    while len(out) < count and time.monotonic() < end:
        try:
            got = s.recv(65536)
        except socket.timeout:
            continue
        except ConnectionResetError:
            closed = True
            break
        if not got:
            closed = True
            break
        buf += got
        while len(buf) >= 6 and len(buf) >= 6 + struct.unpack(">H", buf[4:6])[0]:
            n = 6 + struct.unpack(">H", buf[4:6])[0]
            out.append(buf[:n])
            buf = buf[n:]
    return out, closed


def closed_soon(s, wait):
    """Whether the server closes s within `wait` seconds."""
    s.settimeout(0.05)
    end = time.monotonic() + wait
    while time.monotonic() < end:
        try:
            if s.recv(300) == b"":
                return True
        except socket.timeout:
            pass
        except (ConnectionResetError, OSError):
            return True
    return False


def rt(s, pdu):
    """One request's round trip: (reply, ms); the worst is kept."""
    global worst
    t = time.monotonic()
    try:
        s.sendall(frame(pdu))
    except OSError:
        return None, 0.0
    r, _ = recv_frames(s, 1, 3.0)
    ms = (time.monotonic() - t) * 1000
    worst = max(worst, ms)
    return (r[0] if r else None), ms


def regs(r):
    n = r[8] // 2
    return struct.unpack(">%dH" % n, r[9:9 + 2 * n])


def probe(port, seconds, name):
    """Round trips of reads for `seconds` on one connection; every one must
    come back within LIMIT_MS.  Returns the replies of IR 0-21."""
    s = connect(port)
    seen = []
    end = time.monotonic() + seconds
    while time.monotonic() < end:
        r, ms = rt(s, read_ir(0, 22))
        if not check(r is not None and len(r) == 9 + 44 and r[7] == 4, "%s: no proper reply" % name):
            break
        check(ms <= LIMIT_MS, "%s: a round trip of %.0f ms" % (name, ms))
        seen.append((time.monotonic(), regs(r)))
        time.sleep(0.01)
    s.close()
    return seen


def pipeline(port):
    # 20 reads in one send(): all answered, in order
    for count in (20, 21, 64, 300):
        s = connect(port)
        pdus = [read_ir(0, 1), struct.pack(">BHH", 3, 0, 2), struct.pack(">BHH", 1, 0, 5),
                struct.pack(">BHH", 2, 0, 16), read_ir(600, 125)]
        sent = []
        data = b""
        for i in range(count):
            f = frame(pdus[i % len(pdus)], 1000 + i)
            sent.append((1000 + i, f[7]))
            data += f
        s.sendall(data)
        got, _ = recv_frames(s, count, 3.0)
        check(len(got) == count, "pipeline: %d frames in one send, %d answered" % (count, len(got)))
        check([(struct.unpack(">H", g[:2])[0], g[7]) for g in got] == sent[:len(got)],
              "pipeline: %d frames: replies out of order or wrong" % count)
        s.close()
    # a write the machine takes in the middle: what follows it waits for it,
    # and the read right after it sees the value
    s = connect(port)
    val = 2.625
    w = struct.pack(">BHHB", 16, 104, 4, 8) + struct.pack(">d", val)
    data = frame(read_ir(0, 1), 1) + frame(w, 2) + frame(read_ir(104, 4), 3) + frame(read_ir(0, 1), 4)
    s.sendall(data)
    got, _ = recv_frames(s, 4, 3.0)
    check([struct.unpack(">H", g[:2])[0] for g in got] == [1, 2, 3, 4], "pipeline with a write: %r" % got)
    if len(got) == 4:
        check(got[1][7] == 16, "pipeline: the R1 write was refused (%r)" % got[1])
        check(struct.unpack(">d", got[2][9:17])[0] == val, "pipeline: the read after the write: %r" % got[2])
    s.close()
    # a client that half-closes after its burst still gets every reply
    s = connect(port)
    s.sendall(b"".join(frame(read_ir(0, 1), 50 + i) for i in range(20)))
    s.shutdown(socket.SHUT_WR)
    got, closed = recv_frames(s, 21, 3.0)
    check(len(got) == 20 and closed, "half close: %d of 20 answered, closed %s" % (len(got), closed))
    s.close()


def refused_now(s, wait=1.0):
    """Whether the server refuses s: a request on it gets no reply and the
    connection is closed within `wait` seconds (it is not left hanging)."""
    try:
        s.sendall(frame(read_ir(0, 1)))
    except OSError:
        return True
    got, closed = recv_frames(s, 1, wait)
    return not got and closed


def slots(port, most):
    # a client that talks, then the other slots filled with silent sockets,
    # each from an address of its own
    active = connect(port)
    r, _ = rt(active, read_ir(0, 1))
    check(r is not None, "slots: the first client")
    silent = [connect(port, src="127.0.1.%d" % k) for k in range(most - 1)]
    # for GRACE after it was accepted a connection is active: a newcomer now is refused
    time.sleep(0.1)
    s = connect(port, src="127.0.2.1")
    check(refused_now(s), "slots full of fresh sockets: a newcomer was not refused")
    s.close()
    for c in silent:
        check(not closed_soon(c, 0.01), "slots full of fresh sockets: one was closed for a refused newcomer")
    end = time.monotonic() + GRACE + 0.2
    while time.monotonic() < end:
        r, _ = rt(active, read_ir(0, 1))
        time.sleep(0.1)
    # a newcomer is served at once, and one silent socket (the oldest) goes
    for k in range(min(3, most - 1)):
        s = connect(port, src="127.0.3.%d" % k)
        r, ms = rt(s, read_ir(0, 1))
        check(r is not None and ms <= LIMIT_MS, "slots full: newcomer %d got %r after %.0f ms" % (k, r, ms))
        check(closed_soon(silent[k], 1.0), "slots full: the oldest silent socket %d was not closed" % k)
        silent.append(s)   # it has talked now
        r, ms = rt(active, read_ir(0, 1))
        check(r is not None, "slots full: the client that talks was closed for newcomer %d" % k)
    # everyone has talked; the others talk again after GRACE: the newcomer
    # closes the one silent longest, and only it
    keep = silent[min(3, most - 1):]
    for c in keep:
        rt(c, read_ir(0, 1))
    time.sleep(GRACE + 0.2)
    for c in keep:
        rt(c, read_ir(0, 1))
    s = connect(port, src="127.0.4.1")
    r, ms = rt(s, read_ir(0, 1))
    check(r is not None and ms <= LIMIT_MS, "all talked: the newcomer got %r after %.0f ms" % (r, ms))
    check(closed_soon(active, 1.0), "all talked: the longest silent client was not closed")
    for c in keep:
        r, _ = rt(c, read_ir(0, 1))
        check(r is not None, "all talked: a client that had just asked was closed")
    for c in silent + [s, active]:
        c.close()


class Poller(threading.Thread):
    """A client that reads every `every` seconds (0: as fast as it can)
    until stopped: how many of its polls were answered; on a closed
    connection it connects again, as a panel would."""

    def __init__(self, port, src, every):
        threading.Thread.__init__(self, daemon=True)
        self.port, self.src, self.every = port, src, every
        self.asked = self.answered = self.lost = 0
        self.halt = threading.Event()
        self.s = connect(port, src=src)
        r, _ = rt(self.s, read_ir(0, 1))
        self.first = r is not None

    def run(self):
        while not self.halt.is_set():
            t = time.monotonic()
            self.asked += 1
            r, _ = rt(self.s, read_ir(0, 22))
            if r is not None and len(r) == 9 + 44:
                self.answered += 1
            else:
                self.lost += 1
                self.s.close()
                try:
                    self.s = connect(self.port, src=self.src)
                except OSError:
                    pass
            if self.every:
                self.halt.wait(max(0.0, self.every - (time.monotonic() - t)))

    def stop(self):
        self.halt.set()
        self.join(5)
        self.s.close()


def busy(port):
    """Issue 30: seven busy clients and a loop of fresh connections while a
    panel polls every 100 ms: the panel gets every poll answered, the loop
    is refused (all eight slots are active), nobody busy is closed."""
    hot = [Poller(port, "127.0.0.1", 0) for _ in range(7)]
    check(all(p.first for p in hot), "busy: a busy client was not served")
    panel = Poller(port, "127.0.0.2", 0.1)
    check(panel.first, "busy: the panel was not served")
    for p in hot:
        p.start()
    time.sleep(0.2)
    tries = served = 0
    slowest = 0.0
    panel.start()
    end = time.monotonic() + 5.0
    while time.monotonic() < end:   # fresh connections, from a third address
        t = time.monotonic()
        try:
            s = connect(port, src="127.0.0.3")
        except OSError:
            continue
        tries += 1
        s.sendall(frame(read_ir(0, 1)))
        got, closed = recv_frames(s, 1, 2.0)
        served += len(got) > 0
        if not got:
            slowest = max(slowest, time.monotonic() - t)
        s.close()
        time.sleep(0.005)
    panel.stop()
    for p in hot:
        p.stop()
    print("modbus-robust busy: the panel %d of %d polls answered; %d newcomers, %d served, refused within %.0f ms" %
          (panel.answered, panel.asked, tries, served, slowest * 1000))
    check(panel.asked >= 45 and panel.answered == panel.asked,
          "busy: the panel polling every 100 ms got %d of %d polls answered" % (panel.answered, panel.asked))
    check(all(p.lost == 0 for p in hot), "busy: busy clients lost %s polls" % [p.lost for p in hot])
    check(tries >= 20, "busy: only %d fresh connections in 5 s" % tries)
    check(served == 0, "busy: %d of %d newcomers were served while every slot was active" % (served, tries))
    check(slowest < 1.0, "busy: a refused newcomer waited %.1f s to be closed" % slowest)


def full(port, most):
    """Every slot active (each from its own address): a newcomer is closed
    at once, nobody is closed for it; once one falls silent for GRACE the
    newcomer gets its slot."""
    ps = [Poller(port, "127.0.5.%d" % k, 0.1) for k in range(most)]
    check(all(p.first for p in ps), "full: a client was not served")
    for p in ps:
        p.start()
    time.sleep(0.3)
    for k in range(5):
        s = connect(port, src="127.0.6.1")
        t = time.monotonic()
        check(refused_now(s), "full: newcomer %d was not refused with every slot active" % k)
        check(time.monotonic() - t < 1.0, "full: newcomer %d waited %.1f s" % (k, time.monotonic() - t))
        s.close()
        time.sleep(0.1)
    quiet = ps.pop()                 # the last falls silent, its connection open
    quiet.halt.set()
    quiet.join(5)
    time.sleep(0.2)
    s = connect(port, src="127.0.6.1")
    check(refused_now(s), "full: a newcomer closed a client silent only 0.2 s")
    s.close()
    time.sleep(GRACE)
    s = connect(port, src="127.0.6.2")
    r, ms = rt(s, read_ir(0, 1))
    check(r is not None and ms <= LIMIT_MS, "full: a newcomer beside a client silent 1.2 s got %r" % r)
    check(closed_soon(quiet.s, 1.0), "full: the silent client was not closed for the newcomer")
    for p in ps:
        p.stop()
    check(all(p.lost == 0 and p.answered == p.asked for p in ps),
          "full: active clients lost polls: %s" % [(p.answered, p.asked) for p in ps])
    s.close()
    quiet.s.close()


def perhost(port, most):
    """One address holds at most most-1 slots: its next connection is
    refused while a slot is free, and that slot is another host's; once one
    of its own is idle, a new one of its own replaces it."""
    mine = []
    for k in range(most - 1):
        c = connect(port)
        r, _ = rt(c, read_ir(0, 1))
        check(r is not None, "per host: connection %d of 127.0.0.1 was not served" % k)
        mine.append(c)
    s = connect(port)
    check(refused_now(s), "per host: 127.0.0.1 took all %d slots" % most)
    s.close()
    other = connect(port, src="127.0.0.2")
    r, _ = rt(other, read_ir(0, 1))
    check(r is not None, "per host: another host did not get the free slot")
    # all but the first of 127.0.0.1's keep asking; the first falls idle
    end = time.monotonic() + GRACE + 0.2
    while time.monotonic() < end:
        for c in mine[1:] + [other]:
            rt(c, read_ir(0, 1))
        time.sleep(0.1)
    s = connect(port)
    r, _ = rt(s, read_ir(0, 1))
    check(r is not None, "per host: a connection of 127.0.0.1 did not replace its own idle one")
    check(closed_soon(mine[0], 1.0), "per host: the idle connection of 127.0.0.1 was not closed")
    for c in mine[1:] + [other]:
        r, _ = rt(c, read_ir(0, 1))
        check(r is not None, "per host: an active connection was closed")
    for c in mine + [s, other]:
        c.close()


def idle(port, seconds):
    quiet = connect(port)
    busy = connect(port)
    t0 = time.monotonic()
    closed_at = None
    busy_ok = True
    while time.monotonic() - t0 < seconds * 2 + 1 and busy_ok:
        r, _ = rt(busy, read_ir(0, 1))
        busy_ok = r is not None
        if closed_at is None and closed_soon(quiet, seconds / 4):
            closed_at = time.monotonic() - t0
    check(busy_ok, "idle: the client that kept asking was closed")
    check(closed_at is not None and seconds - 0.1 <= closed_at <= seconds + 0.6,
          "idle: a silent connection closed after %s s, expected %g" % (closed_at, seconds))
    busy.close()
    quiet.close()


def readonly(port):
    s = connect(port)
    writes = [("coil", struct.pack(">BHH", 5, 0, 0xFF00)), ("register", struct.pack(">BHH", 6, 0, 50)),
              ("coils", struct.pack(">BHHBB", 15, 0, 1, 1, 1)),
              ("registers", struct.pack(">BHHB", 16, 104, 4, 8) + struct.pack(">d", 1.0)),
              ("bad coil", struct.pack(">BHH", 5, 9, 0x1234))]
    for name, pdu in writes:
        r, _ = rt(s, pdu)
        check(r is not None and r[7] == pdu[0] | 0x80 and r[8] == 1, "read-only: %s write got %r" % (name, r))
    r, _ = rt(s, read_ir(0, 22))
    check(r is not None and r[7] == 4 and regs(r)[0] == 0x0100, "read-only: a read got %r" % r)
    r, _ = rt(s, struct.pack(">BHH", 1, 0, 5))
    check(r is not None and r[7] == 1 and r[9] == 0, "read-only: the coils read %r" % r)
    s.close()


def refused(port):
    s = connect(port)
    s.sendall(frame(read_ir(0, 1)))
    got, closed = recv_frames(s, 1, 1.0)
    check(not got and closed, "allow list: a client not on it got %r, closed %s" % (got, closed))
    s.close()


def free_port():
    s = socket.socket()
    s.bind(("127.0.0.1", 0))
    p = s.getsockname()[1]
    s.close()
    return p


def launch(argv, stdout):
    """s42 with --modbus on a free port: (process, port, stderr path)."""
    for _ in range(20):
        port = free_port()
        err = "%s/robust-%d.err" % (os.environ.get("TMPDIR", "/tmp"), os.getpid())
        ef = open(err, "wb")
        p = subprocess.Popen(argv + ["--modbus", "127.0.0.1:%d" % port], stdout=stdout, stderr=ef)
        ef.close()
        end = time.monotonic() + 10
        while time.monotonic() < end and p.poll() is None:
            if ("Modbus TCP on 127.0.0.1:%d" % port) in open(err, errors="replace").read():
                return p, port, err
            time.sleep(0.05)
        text = open(err, errors="replace").read()
        p.kill()
        p.wait()
        if "in use" not in text:
            fails.append("s42 did not start: %s" % text)
            return None, 0, err
    fails.append("no free port")
    return None, 0, err


def finish(p, err):
    if p is None:
        return
    p.terminate()
    try:
        p.wait(10)
    except subprocess.TimeoutExpired:
        p.kill()
        p.wait()
        fails.append("s42 did not end on SIGTERM")
    try:
        os.unlink(err)
    except OSError:
        pass


def stall(s42, prog):
    """--trace=json into a pipe nobody reads: the machine stops, the server
    does not."""
    p, port, err = launch([s42, "run", prog, "--trace=json"], subprocess.PIPE)
    if p is None:
        return
    s = connect(port)
    r, _ = rt(s, struct.pack(">BHH", 5, 0, 0xFF00))        # Пуск
    check(r is not None and r[7] == 5, "stall: Пуск got %r" % r)
    # the pipe fills within milliseconds; then the machine's time stands still
    t_prev, still = None, 0
    end = time.monotonic() + 10
    while time.monotonic() < end and still < 3:
        r, _ = rt(s, read_ir(20, 2))
        t = regs(r) if r else None
        still = still + 1 if t is not None and t == t_prev else 0
        t_prev = t
        time.sleep(0.1)
    check(still >= 3, "stall: the machine never stalled on its stdout")
    seen = probe(port, 2.0, "stall: stdout blocked")
    check(len(seen) > 20 and all(v[2] == 1 for _, v in seen), "stall: not running while stalled (%d reads)" % len(seen))
    # a write of R is refused at once (the cycle runs); a write of the
    # override waits for the machine and is refused in time (it is stuck)
    r, ms = rt(s, struct.pack(">BHHB", 16, 104, 4, 8) + struct.pack(">d", 1.0))
    check(r is not None and r[8] == 6 and ms <= LIMIT_MS, "stall: an R write got %r after %.0f ms" % (r, ms))
    r, ms = rt(s, struct.pack(">BHH", 6, 0, 50))
    check(r is not None and r[8] == 6 and ms <= LIMIT_MS, "stall: the override got %r after %.0f ms" % (r, ms))
    # Стоп waits in its coil until the machine can take it
    r, ms = rt(s, struct.pack(">BHH", 5, 1, 0xFF00))
    check(r is not None and r[7] == 5 and ms <= LIMIT_MS, "stall: Стоп got %r after %.0f ms" % (r, ms))
    r, _ = rt(s, struct.pack(">BHH", 1, 0, 5))
    check(r is not None and r[9] == 2, "stall: the Стоп coil reads %r, not pressed" % r)
    # somebody reads the pipe: the machine goes on and takes the Стоп
    threading.Thread(target=lambda: [None for _ in iter(lambda: p.stdout.read(65536), b"")], daemon=True).start()
    state = None
    end = time.monotonic() + 10
    while time.monotonic() < end and state != 2:
        r, _ = rt(s, read_ir(2, 1))
        state = regs(r)[0] if r else None
        time.sleep(0.05)
    check(state == 2, "stall: the Стоп pressed while stalled was not taken (state %s)" % state)
    s.close()
    finish(p, err)


def search(s42, prog, args):
    """A tooth search that computes for seconds: round trips stay short."""
    p, port, err = launch([s42, "run", prog] + args, subprocess.DEVNULL)
    if p is None:
        return
    s = connect(port)
    in_search = 0.0
    last = time.monotonic()
    state = None
    end = time.monotonic() + 180
    while time.monotonic() < end and state != 5 and p.poll() is None:
        r, ms = rt(s, read_ir(0, 22))
        if not check(r is not None and r[7] == 4, "search: no proper reply"):
            break
        check(ms <= LIMIT_MS, "search: a round trip of %.0f ms" % ms)
        v = regs(r)
        state = v[2]
        now = time.monotonic()
        if state == 1 and v[3] == 3:
            in_search += now - last   # the G10 block (N3) runs: the plugin computes
        last = now
        time.sleep(0.01)
    check(state == 5, "search: the program did not reach M2 (state %s)" % state)
    check(in_search >= 0.5, "search: N3 ran only %.2f s: no long search to measure" % in_search)
    print("modbus-robust: the tooth search ran %.1f s" % in_search)
    s.close()
    finish(p, err)


def wait_state(s, want, seconds):
    state = None
    end = time.monotonic() + seconds
    while time.monotonic() < end:
        r, _ = rt(s, read_ir(2, 2))
        state = regs(r) if r else None
        if state and state[0] == want:
            return state
        time.sleep(0.05)
    return state


def tuisearch(port):
    """s42 tui: the terminal's thread computes the search, the server's
    answers."""
    s = connect(port)
    rt(s, struct.pack(">BHH", 5, 0, 0xFF00))                 # Пуск: the cycle starts
    st = wait_state(s, 3, 20)
    check(st == (3, 3), "tui search: no wait for Пуск at N3 (%r)" % (st,))
    rt(s, struct.pack(">BHH", 5, 0, 0xFF00))                 # Пуск: the search
    in_search, last, state = 0.0, time.monotonic(), None
    end = time.monotonic() + 120
    while time.monotonic() < end:
        r, ms = rt(s, read_ir(0, 22))
        if not check(r is not None and r[7] == 4, "tui search: no proper reply"):
            break
        check(ms <= LIMIT_MS, "tui search: a round trip of %.0f ms" % ms)
        v = regs(r)
        now = time.monotonic()
        if v[2] == 1 and v[3] == 3:
            in_search += now - last
        last = now
        if v[2] == 3 and in_search > 0:
            break                 # the search of section 1 is done: it waits for section 2
        time.sleep(0.01)
    check(in_search >= 0.5, "tui search: N3 ran only %.2f s: no long search to measure" % in_search)
    print("modbus-robust: the terminal's tooth search ran %.1f s" % in_search)
    s.close()


def main():
    what = sys.argv[1]
    if what == "pipeline":
        pipeline(int(sys.argv[2]))
    elif what == "slots":
        slots(int(sys.argv[2]), int(sys.argv[3]))
    elif what == "busy":
        busy(int(sys.argv[2]))
    elif what == "full":
        full(int(sys.argv[2]), int(sys.argv[3]))
    elif what == "perhost":
        perhost(int(sys.argv[2]), int(sys.argv[3]))
    elif what == "idle":
        idle(int(sys.argv[2]), float(sys.argv[3]))
    elif what == "readonly":
        readonly(int(sys.argv[2]))
    elif what == "refused":
        refused(int(sys.argv[2]))
    elif what == "probe":
        probe(int(sys.argv[2]), float(sys.argv[3]), "probe")
    elif what == "tuisearch":
        tuisearch(int(sys.argv[2]))
    elif what == "stall":
        stall(sys.argv[2], sys.argv[3])
    elif what == "search":
        search(sys.argv[2], sys.argv[3], sys.argv[4:])
    else:
        sys.exit("robust.py: unknown test '%s'" % what)
    for f in fails:
        print("FAIL modbus-robust %s: %s" % (what, f))
    print("modbus-robust %s: worst round trip %.1f ms; %d passed, %d failed" % (what, worst, passes, len(fails)))
    sys.exit(1 if fails else 0)


main()
