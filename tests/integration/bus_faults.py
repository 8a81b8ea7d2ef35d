#!/usr/bin/env python3
"""Puts one fault on a UDP CAN bus (one 16-byte Linux can_frame per datagram), as a node that
is not the machine's would:
   bus_faults.py GROUP PORT nmt-stop NODE      an NMT stop to the drive NODE
   bus_faults.py GROUP PORT reset NODE         an NMT reset node to the drive NODE
   bus_faults.py GROUP PORT sync-flood SECONDS SYNC frames every millisecond for SECONDS"""
import socket
import struct
import sys
import time

group, port, kind, value = sys.argv[1], int(sys.argv[2]), sys.argv[3], sys.argv[4]
s = socket.socket(socket.AF_INET, socket.SOCK_DGRAM)
s.setsockopt(socket.IPPROTO_IP, socket.IP_MULTICAST_IF, socket.inet_aton("127.0.0.1"))
s.setsockopt(socket.IPPROTO_IP, socket.IP_MULTICAST_TTL, 0)
s.setsockopt(socket.IPPROTO_IP, socket.IP_MULTICAST_LOOP, 1)


def frame(cob_id, data):
    return struct.pack("<IB3x8s", cob_id, len(data), bytes(data).ljust(8, b"\0"))


NMT_STOP, NMT_RESET_NODE = 0x02, 0x81
if kind == "nmt-stop":
    s.sendto(frame(0x000, [NMT_STOP, int(value)]), (group, port))
elif kind == "reset":
    s.sendto(frame(0x000, [NMT_RESET_NODE, int(value)]), (group, port))
elif kind == "sync-flood":
    end = time.monotonic() + float(value)
    counter = 0
    while time.monotonic() < end:
        counter = counter % 240 + 1
        s.sendto(frame(0x080, [counter]), (group, port))
        time.sleep(0.001)
else:
    sys.exit("unknown fault " + kind)
