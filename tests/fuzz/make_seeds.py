#!/usr/bin/env python3
# SPDX-License-Identifier: GPL-2.0
"""Write the hand-made seed corpora of tests/fuzz/corpus/<target>/.

The binary targets read their input as two streams (fuzz_input.h): data
from the front, decisions from the back.  A Script collects both in the
order the target reads them and lays them out that way, so each seed
below reads like the scenario it stands for.  Regression seeds (inputs
that once failed) are committed as found and not written here.

Run it from anywhere: python3 tests/fuzz/make_seeds.py
"""
import os
import struct

CORPUS = os.path.join(os.path.dirname(os.path.abspath(__file__)), "corpus")

# uapi/linux/can/mcp2510.h
RESET, READ, WRITE, BIT_MODIFY = 0xC0, 0x03, 0x02, 0x05
READ_STATUS, RTS, RX_STATUS = 0xA0, 0x80, 0xB0
READ_RX_BUFFER, LOAD_TX_BUFFER = 0x90, 0x40
BFPCTRL, CANSTAT, CANCTRL, TEC = 0x0C, 0x0E, 0x0F, 0x1C
CNF3, CANINTE, CANINTF, EFLG = 0x28, 0x2B, 0x2C, 0x2D
TXB0, RXB0 = 0x30, 0x60
MODE_NORMAL, MODE_SLEEP, MODE_LOOPBACK, MODE_CONFIG = 0, 1, 2, 4
REQOP_MASK, INT_WAK = 0xE0, 0x40
RESET_CANSTAT, MCP2510_RESET_CANCTRL = 0x80, 0xE7
EFF = 0x80000000
# 500 kbit/s from 16 MHz: BRP 1, PRSEG 5, PS1 6, PS2 4, SJW 1 (75 %)
CNF_500K = [0x03, 0xAC, 0x00]     # CNF3, CNF2, CNF1
CAN_ERR_FLAG = 0x20000000


class Script:
    """Data (front) and decisions (back) in the order a target reads them."""

    def __init__(self):
        self.front = bytearray()
        self.decisions = bytearray()

    def u8(self, v):
        self.decisions.append(v & 0xFF)
        return self

    def u16(self, v):
        return self.u8(v >> 8).u8(v)

    def u32(self, v):
        return self.u16(v >> 16).u16(v)

    def data(self, b):
        self.front += bytes(b)
        return self

    def bytes(self):
        return bytes(self.front) + bytes(reversed(self.decisions))


def write(target, name, content):
    path = os.path.join(CORPUS, target)
    os.makedirs(path, exist_ok=True)
    with open(os.path.join(path, name), "wb") as f:
        f.write(content if isinstance(content, bytes) else content.encode())


# ---- sim_spi (fuzz_sim_spi.c) -------------------------------------------
(S_SPI, S_SPI2, S_ADVANCE, S_NEXT, S_PH_SEND, S_PH_FLOOD, S_PH_DETACH,
 S_POWER, S_RTS, S_BUS_FAULTS, S_CHIP_FAULTS) = range(11)
SIM_OSC_16M = 3
STEP_NS = 16


class SimScript(Script):
    def __init__(self, variants=(0, 0), phantom=True, service=False):
        super().__init__()
        self.u8(service)
        for v in variants:
            self.u8(v).u8(SIM_OSC_16M)
        self.u8(phantom)

    def spi(self, chip, *mosi):
        self.u8(S_SPI).u8(chip).u8(0).u8(len(mosi))
        return self.data(mosi)

    def advance_us(self, us):
        ns = us * 1000
        while ns > 0:
            step = min(ns, 0xFFFF * STEP_NS)
            self.u8(S_ADVANCE).u16(step // STEP_NS)
            ns -= step
        return self

    def bring_up(self, chip, mode=MODE_NORMAL):
        self.spi(chip, RESET).advance_us(10)
        self.spi(chip, WRITE, CNF3, *CNF_500K, 0xFF)   # and CANINTE
        return self.spi(chip, BIT_MODIFY, CANCTRL, REQOP_MASK, mode << 5)

    def load_and_send(self, chip, sidh, sidl, data):
        self.spi(chip, WRITE, TXB0 + 1, sidh, sidl, 0, 0, len(data), *data)
        return self.spi(chip, RTS | 1)

    def frame(self, can_id, data):
        self.u32(can_id).u8(len(data))
        for i in range(8):
            self.u8(data[i] if i < len(data) else 0)
        return self


def sim_seeds():
    s = SimScript().bring_up(0).bring_up(1)
    s.load_and_send(0, 0x24, 0x60, [0x11, 0x22, 0x33]).advance_us(300)
    s.spi(1, READ_STATUS, 0).spi(1, READ, RXB0, *[0] * 14)
    s.spi(1, BIT_MODIFY, CANINTF, 0x01, 0x00)
    write("sim_spi", "two-nodes-500k", s.bytes())

    s = SimScript(variants=(1, 1)).bring_up(0).bring_up(1)
    s.spi(0, LOAD_TX_BUFFER, 0x24, 0x60, 0, 0, 2, 0xAA, 0x55)
    s.spi(0, RTS | 1).advance_us(300)
    s.spi(1, RX_STATUS, 0).spi(1, READ_RX_BUFFER, *[0] * 13)
    write("sim_spi", "mcp2515-buffer-instructions", s.bytes())

    s = SimScript(phantom=False).bring_up(0, MODE_LOOPBACK)
    s.load_and_send(0, 0xFF, 0xEB, [1, 2, 3, 4, 5, 6, 7, 8]).advance_us(300)
    s.spi(0, READ, CANINTE, 0, 0, 0)
    write("sim_spi", "loopback-extended", s.bytes())

    s = SimScript(service=True).bring_up(0)
    s.u8(S_PH_FLOOD).frame(0x123, [0, 0, 0, 0]).u8(20).u8(0)
    s.advance_us(3000).spi(0, READ, EFLG, 0).spi(0, READ, TEC, 0, 0)
    write("sim_spi", "flood-overflow", s.bytes())

    s = SimScript(phantom=False).bring_up(0).bring_up(1)
    s.u8(S_BUS_FAULTS).u8(3).u8(1)
    s.load_and_send(0, 0x10, 0x00, [0xFF])
    for _ in range(40):
        s.u8(S_NEXT)
    s.spi(0, READ, TEC, 0, 0).spi(0, READ, EFLG, 0)
    write("sim_spi", "no-ack-error-passive", s.bytes())

    s = SimScript().bring_up(0).spi(0, BIT_MODIFY, CANCTRL, REQOP_MASK,
                                    MODE_SLEEP << 5).advance_us(50)
    s.spi(0, BIT_MODIFY, CANINTF, INT_WAK, INT_WAK).advance_us(50)
    s.spi(0, READ, CANSTAT, 0)
    write("sim_spi", "sleep-wake", s.bytes())

    s = SimScript().bring_up(0).spi(0, READ, 0x7E, *[0] * 136)
    s.spi(0, WRITE, 0x7F, 0x12, 0x34).u8(S_POWER).u8(0).u8(0)
    s.spi(0, READ, CANSTAT, 0).u8(S_POWER).u8(0).u8(1).spi(0, READ, 0x0E, 0)
    write("sim_spi", "wrap-and-power-cycle", s.bytes())


# ---- core_hostile (fuzz_core_hostile.c, fuzz_hostile.h) -----------------
(H_HW_RESET, H_SET_MODE, H_START, H_STOP, H_RESTART, H_IRQ, H_IRQ2,
 H_TX_SUBMIT, H_SLEEP, H_BERR, H_DUMP, H_PIN_BF, H_PIN_RTS,
 H_FILTERS, H_PEER, H_WAKE_ARM, H_WAKE_ACK, H_GARBLE) = range(18)
MODEL_MCP2510, MODEL_MCP2515 = 0, 1
MISO_INPUT, MISO_STUCK, MISO_MODEL = 0, 1, 2
CORE_OSC_16M = 2
CTRLMODE_LOOPBACK, CTRLMODE_ONE_SHOT, CTRLMODE_BERR = 0x01, 0x08, 0x10


class CoreScript(Script):
    def __init__(self, model, miso, fill=0, fail_every=0, edge=False):
        super().__init__()
        self.u8(model).u8(CORE_OSC_16M).u8(miso).u8(fill).u8(fail_every)
        self.u8(edge)

    def start(self, ctrlmode=0):
        # ctrlmode, then BRP, PRSEG, PS1, PS2, SJW for 500 kbit/s
        return self.u8(H_START).u8(ctrlmode).u8(1).u8(5).u8(6).u8(4).u8(1)

    def submit(self, can_id, data):
        self.u8(H_TX_SUBMIT).u32(can_id).u8(len(data))
        for i in range(8):
            self.u8(data[i] if i < len(data) else 0)
        return self

    def peer(self, can_id, data, wait_us=300):
        self.u8(H_PEER).u32(can_id).u8(len(data))
        for b in data:
            self.u8(b)
        return self.u16(wait_us)

    def op(self, *ops):
        for o in ops:
            self.u8(o)
        return self


def core_seeds():
    for model, name in ((MODEL_MCP2510, "mcp2510"), (MODEL_MCP2515, "mcp2515")):
        s = CoreScript(model, MISO_MODEL).start()
        s.submit(0x123, [1, 2]).submit(0x124, [3]).submit(EFF | 0x1234567, [])
        s.submit(0x125, [4]).op(H_IRQ).peer(0x321, [9, 8, 7]).op(H_IRQ)
        s.peer(EFF | 0x7654321, [1]).peer(0x10, []).op(H_IRQ, H_BERR)
        s.op(H_GARBLE).u8(1).op(H_IRQ, H_STOP)
        write("core_hostile", "model-traffic-" + name, s.bytes())

    s = CoreScript(MODEL_MCP2515, MISO_MODEL, edge=True)
    s.start(CTRLMODE_LOOPBACK | CTRLMODE_ONE_SHOT | CTRLMODE_BERR)
    for i in range(6):
        # the peer's frame only lets time pass: loopback hears nobody
        s.submit(0x100 + i, [i]).peer(0x7FF, []).op(H_IRQ)
    s.op(H_RESTART, H_SLEEP, H_DUMP, H_PIN_RTS).u8(1)
    write("core_hostile", "model-loopback-one-shot-edge", s.bytes())

    s = CoreScript(MODEL_MCP2510, MISO_MODEL).start()
    s.op(H_FILTERS).u32(0).u32(0)
    s.u8(0).u8(1).u8(0).u8(1).u8(0).u8(1).u8(1)
    s.submit(0x1, [0]).op(H_GARBLE).u8(3).op(H_IRQ, H_IRQ, H_PIN_BF)
    s.u8(0).u8(1)
    write("core_hostile", "model-garbled-flags", s.bytes())

    # A chip that passes bring-up, then claims a frame in each buffer with
    # DLC 15 and, once the input runs out, every flag for ever.
    reset_ok = [0, 0, RESET_CANSTAT, MCP2510_RESET_CANCTRL]
    normal = [0, 0, MODE_NORMAL << 5]
    rxb = [0, 0, 0xFF, 0xEB, 0xFF, 0xFF, 0x4F] + [0xA5] * 8
    s = CoreScript(MODEL_MCP2510, MISO_INPUT, fill=0xFF, edge=True).start()
    s.data(reset_ok + normal + [0, 0x03] + rxb + rxb).op(H_IRQ, H_IRQ)
    write("core_hostile", "garbage-dlc15-stuck-int", s.bytes())

    for fill in (0x00, 0xFF):
        s = CoreScript(MODEL_MCP2515, MISO_STUCK, fill=fill, edge=True)
        s.op(H_HW_RESET, H_SET_MODE).u8(MODE_NORMAL).op(H_IRQ, H_SLEEP)
        write("core_hostile", "stuck-miso-%02x" % fill, s.bytes())

    # wake-on-CAN: stop, arm (with WAKFIL asked for), a peer's frame
    # wakes the chip, acknowledge, start again
    s = CoreScript(MODEL_MCP2515, MISO_MODEL).start()
    s.op(H_STOP, H_WAKE_ARM).u8(1).peer(0x123, [1]).op(H_WAKE_ACK, H_IRQ)
    s.op(H_WAKE_ACK).start()
    write("core_hostile", "model-wake-on-bus", s.bytes())

    s = CoreScript(MODEL_MCP2510, MISO_MODEL, fail_every=3).start()
    s.submit(0x7FF, [0xFF] * 8).op(H_IRQ, H_RESTART, H_IRQ, H_STOP)
    write("core_hostile", "model-transfer-errors", s.bytes())


# ---- text and timing ------------------------------------------------------
def text_seeds():
    for name, text in (("standard", "123#DEADBEEF"), ("extended", "12345678#11"),
                       ("empty", "123#"), ("dots", "123#11.22.33"),
                       ("remote", "123#R"), ("remote-len", "7FF#R8"),
                       ("fd-refused", "123##1"), ("error-refused", "20000000#")):
        write("frame_text", name, text)
    for name, text in (("std-max", "7ff"), ("ext-max", "1fffffffx"),
                       ("sysfs-newline", "0\n"), ("rxm-any", "any\n"),
                       ("rxm-filtered", "filtered")):
        write("filter_text", name, text)


def bittiming_seeds():
    s = Script()
    s.u8(0)                                  # encode
    for v in (5, 6, 4, 1, 1, 0x04):          # PRSEG PS1 PS2 SJW BRP, 3 samples
        s.u32(v)
    write("bittiming", "encode-500k", s.bytes())
    for name, clock, rate, sp, sjw in (("calc-500k-16mhz", 8000000, 500000, 0, 0),
                                       ("calc-1m-sp750-sjw4", 8000000, 1000000, 750, 4),
                                       ("calc-impossible", 8000000, 5000000, 0, 0),
                                       ("calc-10k-25mhz", 12500000, 10000, 875, 1)):
        s = Script().u8(1).u32(clock).u32(rate).u32(sp).u8(sjw)
        write("bittiming", name, s.bytes())


if __name__ == "__main__":
    sim_seeds()
    core_seeds()
    text_seeds()
    bittiming_seeds()
