#!/usr/bin/env python3
"""Malformed and hostile Modbus TCP traffic against a running s42 --modbus
server, while a second client keeps measuring its own round trips: each
frame must get its exception or close only its own connection, no round
trip of the other client may exceed 150 ms, and the server must be alive
at the end.   raw.py PORT"""
import socket
import struct
import sys
import time

PORT = int(sys.argv[1])
LIMIT_MS = 150.0
fails = []
passes = 0
worst = 0.0
tid = 0


def connect():
    s = socket.create_connection(("127.0.0.1", PORT), timeout=3)
    s.setsockopt(socket.IPPROTO_TCP, socket.TCP_NODELAY, 1)
    return s


def frame(pdu, unit=1, proto=0, length=None):
    global tid
    tid = (tid + 1) & 0xFFFF
    n = len(pdu) + 1 if length is None else length
    return struct.pack(">HHHB", tid, proto, n, unit) + pdu


def recv_reply(s, timeout=2.0):
    """One reply frame, b'' when the server closed the connection, None on
    a timeout."""
    s.settimeout(timeout)
    buf = b""
    try:
        while len(buf) < 6 or len(buf) < 6 + struct.unpack(">H", buf[4:6])[0]:
            got = s.recv(300)
            if not got:
                return b""
            buf += got
    except socket.timeout:
        return None
    except ConnectionResetError:
        return b""
    return buf


victim = connect()


def probe():
    """One timed read by the second client; returns its round trip in ms."""
    global worst
    t = time.monotonic()
    victim.sendall(frame(struct.pack(">BHH", 4, 0, 22)))
    r = recv_reply(victim)
    ms = (time.monotonic() - t) * 1000
    if not r or len(r) != 9 + 44 or r[7] != 4:
        fails.append("the second client got no proper reply (%r)" % (r,))
        return ms
    worst = max(worst, ms)
    return ms


def probe_for(seconds):
    end = time.monotonic() + seconds
    while time.monotonic() < end:
        ms = probe()
        if ms > LIMIT_MS:
            fails.append("the second client waited %.0f ms" % ms)
        time.sleep(0.01)


def expect(name, data, want, wait=0.6):
    """Send data on a fresh connection; want: ('ex', code) an exception
    reply then a working connection, or 'close' (closed within `wait` s).
    The second client probes meanwhile."""
    global passes
    s = connect()
    s.sendall(data)
    t0 = time.monotonic()
    probe_for(0.05)
    if want == "close":
        s.settimeout(0.02)
        closed = False
        while time.monotonic() - t0 < wait + 0.5 and not closed:
            try:
                if s.recv(300) == b"":   # an exception reply may come first
                    closed = True
            except socket.timeout:
                probe()
            except ConnectionResetError:
                closed = True
        ok = closed
        why = "the connection was not closed"
    else:
        r = recv_reply(s)
        ok = bool(r) and len(r) == 9 and r[7] & 0x80 and r[8] == want[1]
        why = "expected exception %02x, got %r" % (want[1], r)
        if ok:   # the connection goes on
            s.sendall(frame(struct.pack(">BHH", 4, 0, 1)))
            r2 = recv_reply(s)
            ok = bool(r2) and r2[7] == 4
            why = "the connection did not go on after the exception"
    s.close()
    if ok:
        passes += 1
    else:
        fails.append("%s: %s" % (name, why))


read_ir = struct.pack(">BHH", 4, 0, 1)
cases = [
    ("protocol id 1", frame(read_ir, proto=1), "close"),
    ("length field 0", frame(read_ir, length=0), "close"),
    ("length field 1", frame(read_ir, length=1), "close"),
    ("length field 0xFFFF", frame(read_ir, length=0xFFFF), "close"),
    ("length field says more than sent", frame(read_ir, length=20), "close"),
    ("truncated header", frame(read_ir)[:5], "close"),
    ("truncated PDU", frame(read_ir)[:9], "close"),
    ("length field says less than sent", frame(read_ir, length=3) + b"\x07\x07\x07", "close"),
    ("garbage", bytes(range(7, 250)), "close"),
    ("zeros", bytes(4096), "close"),
    ("unknown function 0x2B", frame(b"\x2B\x0E\x01\x00"), ("ex", 1)),
    ("function 0x81", frame(b"\x81\x00\x00\x00\x01"), ("ex", 1)),
    ("function 0x17 (read/write)", frame(b"\x17" + bytes(9) + b"\x00"), ("ex", 1)),
    ("quantity 0", frame(struct.pack(">BHH", 4, 0, 0)), ("ex", 3)),
    ("quantity 126", frame(struct.pack(">BHH", 3, 100, 126)), ("ex", 3)),
    ("bits quantity 2001", frame(struct.pack(">BHH", 2, 0, 2001)), ("ex", 3)),
    ("read PDU too long", frame(struct.pack(">BHHB", 4, 0, 1, 0)), ("ex", 3)),
    ("read PDU too short", frame(b"\x04\x00"), ("ex", 3)),
    ("input register 22", frame(struct.pack(">BHH", 4, 22, 1)), ("ex", 2)),
    ("input registers across a gap", frame(struct.pack(">BHH", 4, 20, 90)), ("ex", 2)),
    ("address 65535 quantity 125", frame(struct.pack(">BHH", 4, 65535, 125)), ("ex", 2)),
    ("coil 6", frame(struct.pack(">BHH", 5, 6, 0xFF00)), ("ex", 2)),
    ("coil value 0x1234", frame(struct.pack(">BHH", 5, 0, 0x1234)), ("ex", 3)),
    ("FC15 byte count lies", frame(struct.pack(">BHHB", 15, 0, 5, 2) + b"\x00\x00"), ("ex", 3)),
    ("FC16 byte count lies", frame(struct.pack(">BHHB", 16, 0, 1, 4) + b"\x00\x05"), ("ex", 3)),
    ("FC16 half a float64", frame(struct.pack(">BHHB", 16, 100, 2, 4) + bytes(4)), ("ex", 2)),
    ("FC16 float64 misaligned", frame(struct.pack(">BHHB", 16, 102, 4, 8) + bytes(8)), ("ex", 2)),
    ("FC16 float32 odd address", frame(struct.pack(">BHHB", 16, 601, 2, 4) + bytes(4)), ("ex", 2)),
    ("FC16 NaN", frame(struct.pack(">BHHB", 16, 100, 4, 8) + b"\x7f\xf8" + bytes(6)), ("ex", 3)),
    ("FC16 float32 inf", frame(struct.pack(">BHHB", 16, 600, 2, 4) + b"\x7f\x80\x00\x00"), ("ex", 3)),
    ("FC6 override 1000", frame(struct.pack(">BHH", 6, 0, 1000)), ("ex", 3)),
    ("FC6 into a float64", frame(struct.pack(">BHH", 6, 100, 1)), ("ex", 2)),
    ("unit id 7", frame(read_ir, unit=7), ("ex", 0x0B)),
]

for name, data, want in cases:
    expect(name, data, want)

# A slow writer: one byte every 100 ms.
s = connect()
data = frame(read_ir)
closed = False
for b in data:
    try:
        s.sendall(bytes([b]))
    except OSError:
        closed = True
        break
    probe_for(0.1)
s.settimeout(1)
try:
    closed = closed or s.recv(300) == b""
except (socket.timeout, ConnectionResetError):
    closed = closed or False
if closed:
    passes += 1
else:
    fails.append("a client sending one byte per 100 ms was not cut off")
s.close()

# More clients than the limit from one address: it holds at most 7 of the
# 8 places (the victim, which talks and goes on, is one), and newcomers
# past that are refused while the others are fresh (active for a second).
many = [connect() for _ in range(12)]
probe_for(0.1)
refused = 0
for c in many:
    c.settimeout(0.3)
    try:
        if c.recv(10) == b"":
            refused += 1
    except socket.timeout:
        pass
    except ConnectionResetError:
        refused += 1
for c in many:
    c.close()
if refused >= 12 - 7:   # the victim holds one of the 8 places
    passes += 1
else:
    fails.append("only %d of 12 extra clients were refused" % refused)

# A flood of requests whose replies are never read: the server stops
# reading it and finally drops it; others are not held up.
s = connect()
s.setblocking(False)
req = frame(struct.pack(">BHH", 4, 100, 125))
sent = 0
t0 = time.monotonic()
while time.monotonic() - t0 < 1.0:
    try:
        sent += s.send(req * 50)
    except BlockingIOError:
        probe()
        time.sleep(0.01)
    except OSError:
        break
probe_for(2.5)
s.close()
passes += 1

# Alive at the end.
ms = probe()
if ms <= LIMIT_MS:
    passes += 1
victim.close()

for f in fails:
    print("FAIL modbus-raw: " + f)
print("modbus-raw: the other client's worst round trip %.1f ms" % worst)
print("modbus-raw: %d passed, %d failed" % (passes, len(fails)))
sys.exit(1 if fails else 0)
