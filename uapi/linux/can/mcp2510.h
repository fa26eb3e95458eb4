/* SPDX-License-Identifier: GPL-2.0 WITH Linux-syscall-note */
/*
 * Microchip MCP2510 / MCP2515 / MCP25625 stand-alone CAN controller:
 * register map, SPI instructions and bit fields, shared by the kernel
 * driver, the userspace library and the simulated chip.
 *
 * Facts from the MCP2510 data sheet (DS21291), the MCP2515 data sheet
 * (DS21801) and application note AN739.
 *
 * Conventions: MCP2510_REG_* are register addresses, *_MASK are field
 * masks (use FIELD_PREP/FIELD_GET), other field names are unshifted field
 * values, single bits are BIT(n) values.  Bit and mask macros are written
 * as plain constants so the header needs no kernel helpers.
 */
#ifndef _UAPI_LINUX_CAN_MCP2510_H
#define _UAPI_LINUX_CAN_MCP2510_H

#include <linux/types.h>

/* ---- SPI instructions ------------------------------------------------ */

#define MCP2510_INSTR_RESET		0xc0
#define MCP2510_INSTR_READ		0x03	/* addr, then data out */
#define MCP2510_INSTR_WRITE		0x02	/* addr, then data in */
#define MCP2510_INSTR_RTS		0x80	/* | MCP2510_RTS_TXB(n) */
#define MCP2510_INSTR_READ_STATUS	0xa0
#define MCP2510_INSTR_BIT_MODIFY	0x05	/* addr, mask, data */
/* MCP2515 and MCP25625 only; an MCP2510 ignores them. */
#define MCP2515_INSTR_READ_RX_BUFFER	0x90	/* | MCP2515_READ_RXB_*() */
#define MCP2515_INSTR_LOAD_TX_BUFFER	0x40	/* | MCP2515_LOAD_TXB_*() */
#define MCP2515_INSTR_RX_STATUS		0xb0

#define MCP2510_RTS_TXB(n)		(1 << (n))
#define MCP2510_RTS_ALL			0x07
/* READ RX BUFFER starts at RXBnSIDH or RXBnD0 and clears RXnIF at CS high */
#define MCP2515_READ_RXB_SIDH(n)	((n) << 2)
#define MCP2515_READ_RXB_D0(n)		(((n) << 2) | 0x02)
/* LOAD TX BUFFER starts at TXBnSIDH or TXBnD0 */
#define MCP2515_LOAD_TXB_SIDH(n)	((n) << 1)
#define MCP2515_LOAD_TXB_D0(n)		(((n) << 1) | 0x01)

/* READ STATUS: one byte, repeated while the clock runs */
#define MCP2510_STATUS_RX0IF		0x01
#define MCP2510_STATUS_RX1IF		0x02
#define MCP2510_STATUS_TX0REQ		0x04
#define MCP2510_STATUS_TX0IF		0x08
#define MCP2510_STATUS_TX1REQ		0x10
#define MCP2510_STATUS_TX1IF		0x20
#define MCP2510_STATUS_TX2REQ		0x40
#define MCP2510_STATUS_TX2IF		0x80
#define MCP2510_STATUS_TXREQ(n)		(0x04 << (2 * (n)))
#define MCP2510_STATUS_TXIF(n)		(0x08 << (2 * (n)))

/* RX STATUS (MCP2515): which buffer, frame type, filter hit */
#define MCP2515_RXSTATUS_RXB_MASK	0xc0
#define MCP2515_RXSTATUS_RXB0		0x40
#define MCP2515_RXSTATUS_RXB1		0x80
#define MCP2515_RXSTATUS_TYPE_MASK	0x18
#define MCP2515_RXSTATUS_TYPE_STD	0
#define MCP2515_RXSTATUS_TYPE_STD_RTR	1
#define MCP2515_RXSTATUS_TYPE_EXT	2
#define MCP2515_RXSTATUS_TYPE_EXT_RTR	3
#define MCP2515_RXSTATUS_FILHIT_MASK	0x07
#define MCP2515_RXSTATUS_FILHIT_RXF0_RB1 6	/* RXF0 hit, rolled into RXB1 */
#define MCP2515_RXSTATUS_FILHIT_RXF1_RB1 7	/* RXF1 hit, rolled into RXB1 */

/* ---- Register map ---------------------------------------------------- */

#define MCP2510_REG_COUNT		0x80

/* Acceptance filters and masks: four registers each, SIDH first. */
#define MCP2510_REG_RXF(n)		((n) < 3 ? 4 * (n) : 0x10 + 4 * ((n) - 3))
#define MCP2510_REG_RXFSIDH(n)		(MCP2510_REG_RXF(n) + MCP2510_ID_SIDH)
#define MCP2510_REG_RXFSIDL(n)		(MCP2510_REG_RXF(n) + MCP2510_ID_SIDL)
#define MCP2510_REG_RXFEID8(n)		(MCP2510_REG_RXF(n) + MCP2510_ID_EID8)
#define MCP2510_REG_RXFEID0(n)		(MCP2510_REG_RXF(n) + MCP2510_ID_EID0)
#define MCP2510_REG_RXM(n)		(0x20 + 4 * (n))
#define MCP2510_REG_RXMSIDH(n)		(MCP2510_REG_RXM(n) + MCP2510_ID_SIDH)
#define MCP2510_REG_RXMSIDL(n)		(MCP2510_REG_RXM(n) + MCP2510_ID_SIDL)
#define MCP2510_REG_RXMEID8(n)		(MCP2510_REG_RXM(n) + MCP2510_ID_EID8)
#define MCP2510_REG_RXMEID0(n)		(MCP2510_REG_RXM(n) + MCP2510_ID_EID0)
#define MCP2510_FILTER_COUNT		6
#define MCP2510_MASK_COUNT		2

#define MCP2510_REG_BFPCTRL		0x0c
#define MCP2510_REG_TXRTSCTRL		0x0d
/* CANSTAT and CANCTRL also read at 0xXe / 0xXf of every row. */
#define MCP2510_REG_CANSTAT		0x0e
#define MCP2510_REG_CANCTRL		0x0f
#define MCP2510_REG_TEC			0x1c
#define MCP2510_REG_REC			0x1d
#define MCP2510_REG_CNF3		0x28
#define MCP2510_REG_CNF2		0x29
#define MCP2510_REG_CNF1		0x2a
#define MCP2510_REG_CANINTE		0x2b
#define MCP2510_REG_CANINTF		0x2c
#define MCP2510_REG_EFLG		0x2d

/* Transmit buffers 0-2 and receive buffers 0-1: 14 registers each. */
#define MCP2510_TXB_COUNT		3
#define MCP2510_RXB_COUNT		2
#define MCP2510_REG_TXB(n)		(0x30 + 0x10 * (n))
#define MCP2510_REG_RXB(n)		(0x60 + 0x10 * (n))
#define MCP2510_REG_TXBCTRL(n)		MCP2510_REG_TXB(n)
#define MCP2510_REG_TXBSIDH(n)		(MCP2510_REG_TXB(n) + MCP2510_BUF_SIDH)
#define MCP2510_REG_TXBDLC(n)		(MCP2510_REG_TXB(n) + MCP2510_BUF_DLC)
#define MCP2510_REG_TXBD(n, i)		(MCP2510_REG_TXB(n) + MCP2510_BUF_D0 + (i))
#define MCP2510_REG_RXBCTRL(n)		MCP2510_REG_RXB(n)
#define MCP2510_REG_RXBSIDH(n)		(MCP2510_REG_RXB(n) + MCP2510_BUF_SIDH)
#define MCP2510_REG_RXBDLC(n)		(MCP2510_REG_RXB(n) + MCP2510_BUF_DLC)
#define MCP2510_REG_RXBD(n, i)		(MCP2510_REG_RXB(n) + MCP2510_BUF_D0 + (i))

/* Offsets inside an identifier block (filter, mask) */
#define MCP2510_ID_SIDH			0
#define MCP2510_ID_SIDL			1
#define MCP2510_ID_EID8			2
#define MCP2510_ID_EID0			3
#define MCP2510_ID_LEN			4

/* Offsets inside a transmit or receive buffer */
#define MCP2510_BUF_CTRL		0
#define MCP2510_BUF_SIDH		1
#define MCP2510_BUF_SIDL		2
#define MCP2510_BUF_EID8		3
#define MCP2510_BUF_EID0		4
#define MCP2510_BUF_DLC			5
#define MCP2510_BUF_D0			6
#define MCP2510_BUF_DATA_LEN		8
#define MCP2510_BUF_LEN			14	/* CTRL .. D7 */

/* ---- Bit fields -------------------------------------------------------- */

/* BFPCTRL: RXnBF pin control */
#define MCP2510_BFPCTRL_B1BFS		0x20	/* pin level in digital-output mode */
#define MCP2510_BFPCTRL_B0BFS		0x10
#define MCP2510_BFPCTRL_B1BFE		0x08	/* pin function enable */
#define MCP2510_BFPCTRL_B0BFE		0x04
#define MCP2510_BFPCTRL_B1BFM		0x02	/* 1: buffer-full interrupt, 0: output */
#define MCP2510_BFPCTRL_B0BFM		0x01
#define MCP2510_BFPCTRL_BFS(n)		(0x10 << (n))
#define MCP2510_BFPCTRL_BFE(n)		(0x04 << (n))
#define MCP2510_BFPCTRL_BFM(n)		(0x01 << (n))

/* TXRTSCTRL: TXnRTS pin control and state */
#define MCP2510_TXRTSCTRL_B2RTS		0x20	/* pin level, read only */
#define MCP2510_TXRTSCTRL_B1RTS		0x10
#define MCP2510_TXRTSCTRL_B0RTS		0x08
#define MCP2510_TXRTSCTRL_B2RTSM	0x04	/* 1: request to send, 0: input */
#define MCP2510_TXRTSCTRL_B1RTSM	0x02
#define MCP2510_TXRTSCTRL_B0RTSM	0x01
#define MCP2510_TXRTSCTRL_BRTS(n)	(0x08 << (n))
#define MCP2510_TXRTSCTRL_BRTSM(n)	(0x01 << (n))

/* CANSTAT */
#define MCP2510_CANSTAT_OPMOD_MASK	0xe0
#define MCP2510_CANSTAT_ICOD_MASK	0x0e
#define MCP2510_ICOD_NONE		0
#define MCP2510_ICOD_ERR		1
#define MCP2510_ICOD_WAKE		2
#define MCP2510_ICOD_TXB0		3
#define MCP2510_ICOD_TXB1		4
#define MCP2510_ICOD_TXB2		5
#define MCP2510_ICOD_RXB0		6
#define MCP2510_ICOD_RXB1		7

/* CANCTRL */
#define MCP2510_CANCTRL_REQOP_MASK	0xe0
#define MCP2510_CANCTRL_ABAT		0x10
#define MCP2515_CANCTRL_OSM		0x08	/* one-shot mode, not on MCP2510 */
#define MCP2510_CANCTRL_CLKEN		0x04
#define MCP2510_CANCTRL_CLKPRE_MASK	0x03

/* Operating modes, for CANCTRL.REQOP and CANSTAT.OPMOD */
#define MCP2510_MODE_NORMAL		0
#define MCP2510_MODE_SLEEP		1
#define MCP2510_MODE_LOOPBACK		2
#define MCP2510_MODE_LISTEN_ONLY	3
#define MCP2510_MODE_CONFIG		4
#define MCP2510_MODE_POWERUP		7	/* REQOP after power-up only */

/* CNF1 */
#define MCP2510_CNF1_SJW_MASK		0xc0	/* SJW - 1 */
#define MCP2510_CNF1_BRP_MASK		0x3f	/* BRP - 1, TQ = 2 (BRP) / Fosc */
/* CNF2 */
#define MCP2510_CNF2_BTLMODE		0x80	/* PS2 from CNF3, not max(PS1, IPT) */
#define MCP2510_CNF2_SAM		0x40	/* sample three times */
#define MCP2510_CNF2_PHSEG1_MASK	0x38	/* PS1 - 1 */
#define MCP2510_CNF2_PRSEG_MASK		0x07	/* PRSEG - 1 */
/* CNF3 */
#define MCP2515_CNF3_SOF		0x80	/* CLKOUT is SOF signal, MCP2515 */
#define MCP2510_CNF3_WAKFIL		0x40
#define MCP2510_CNF3_PHSEG2_MASK	0x07	/* PS2 - 1 */

/* CANINTE and CANINTF share the layout */
#define MCP2510_INT_MERR		0x80
#define MCP2510_INT_WAK			0x40
#define MCP2510_INT_ERR			0x20
#define MCP2510_INT_TX2			0x10
#define MCP2510_INT_TX1			0x08
#define MCP2510_INT_TX0			0x04
#define MCP2510_INT_RX1			0x02
#define MCP2510_INT_RX0			0x01
#define MCP2510_INT_TX(n)		(0x04 << (n))
#define MCP2510_INT_RX(n)		(0x01 << (n))
#define MCP2510_INT_TX_ALL		0x1c
#define MCP2510_INT_RX_ALL		0x03

/* EFLG */
#define MCP2510_EFLG_RX1OVR		0x80
#define MCP2510_EFLG_RX0OVR		0x40
#define MCP2510_EFLG_TXBO		0x20
#define MCP2510_EFLG_TXEP		0x10
#define MCP2510_EFLG_RXEP		0x08
#define MCP2510_EFLG_TXWAR		0x04
#define MCP2510_EFLG_RXWAR		0x02
#define MCP2510_EFLG_EWARN		0x01
#define MCP2510_EFLG_RXOVR(n)		(0x40 << (n))

/* TXBnCTRL */
#define MCP2510_TXBCTRL_ABTF		0x40
#define MCP2510_TXBCTRL_MLOA		0x20
#define MCP2510_TXBCTRL_TXERR		0x10
#define MCP2510_TXBCTRL_TXREQ		0x08
#define MCP2510_TXBCTRL_TXP_MASK	0x03	/* 3 is the highest priority */

/* RXBnCTRL */
#define MCP2510_RXBCTRL_RXM_MASK	0x60
#define MCP2510_RXM_FILTERED		0	/* std and ext frames through filters */
#define MCP2510_RXM_STD			1	/* only std frames through filters */
#define MCP2510_RXM_EXT			2	/* only ext frames through filters */
#define MCP2510_RXM_ANY			3	/* filters off, all frames */
#define MCP2510_RXBCTRL_RXRTR		0x08	/* remote frame received, read only */
#define MCP2510_RXB0CTRL_BUKT		0x04	/* roll over into RXB1 when full */
#define MCP2510_RXB0CTRL_BUKT1		0x02	/* read-only copy of BUKT */
#define MCP2510_RXB0CTRL_FILHIT0	0x01	/* RXF0 (0) or RXF1 (1) */
#define MCP2510_RXB1CTRL_FILHIT_MASK	0x07	/* RXF0..RXF5 */

/* SIDL of a buffer, filter or mask */
#define MCP2510_SIDL_SID_MASK		0xe0	/* SID2..SID0 */
#define MCP2510_SIDL_SRR		0x10	/* RX: standard remote frame */
#define MCP2510_SIDL_EXIDE		0x08	/* TX, filter: extended id; RX: IDE */
#define MCP2510_SIDL_EID_MASK		0x03	/* EID17..EID16 */

/* DLC of a buffer */
#define MCP2510_DLC_RTR			0x40	/* TX: remote; RX: extended remote */
#define MCP2510_DLC_RB1			0x20	/* reserved bits, RX only */
#define MCP2510_DLC_RB0			0x10
#define MCP2510_DLC_MASK		0x0f

/* ---- Reset values (DS21291 register summary) ------------------------- */

#define MCP2510_RESET_CANCTRL		0xe7	/* REQOP 0b111 on power-up */
#define MCP2515_RESET_CANCTRL		0x87
#define MCP2510_RESET_CANSTAT		0x80

/* ---- Identifier encoding ----------------------------------------------
 * Standard id (11 bit): SIDH = SID10..SID3, SIDL.SID = SID2..SID0.
 * Extended id (29 bit): the standard part holds id bits 28..18,
 * SIDL.EID = bits 17..16, EID8 = bits 15..8, EID0 = bits 7..0.
 */
#define MCP2510_SID_SHIFT_SIDH		3
#define MCP2510_SID_SHIFT_SIDL		5
#define MCP2510_EID_BITS		18

/* ---- ethtool register dump (ethtool -d) --------------------------------
 * The dump is the whole register file, MCP2510_REG_COUNT bytes, byte i
 * holding the register at address i, read in one sequential READ while the
 * interface runs.  Its version field is MCP2510_REGDUMP_VERSION.
 */
#define MCP2510_REGDUMP_VERSION		1
#define MCP2510_REGDUMP_LEN		MCP2510_REG_COUNT

/* ---- Hardware acceptance filters (sysfs) ---------------------------------
 * /sys/class/net/canX/mcp2510/ holds, writable only while the interface is
 * down and only with CAP_NET_ADMIN:
 *
 *   mask0, mask1       mask of RXB0 / RXB1
 *   filter0..filter5   RXB0 uses filters 0-1, RXB1 filters 2-5
 *   rxm0, rxm1         receive mode of RXB0 / RXB1: "filtered", "std",
 *                      "ext" or "any" (filters off)
 *   rollover           "1" lets a frame for a full RXB0 go to RXB1 (BUKT)
 *
 * A mask or filter is written and read as a hexadecimal identifier:
 * "7ff" is a standard (11 bit) one, "1fffffffx" (trailing x) an extended
 * (29 bit) one.  A standard filter accepts only standard frames and an
 * extended filter only extended ones (EXIDE).  A standard mask compares the
 * 11 identifier bits (of an extended frame: its top 11 bits), an extended
 * mask all 29.  A set mask bit means the identifier bit must equal the
 * filter's.  A filter takes only frames of its own format even when its
 * mask is 0, so the default, which accepts every frame, has both masks 0
 * (no bit must match), filters 0, 2 and 4 standard and 1, 3 and 5
 * extended (all 0), both buffers "filtered" and rollover 1.  Anything else
 * is refused with EINVAL and leaves the previous setting.
 */
#define MCP2510_SYSFS_GROUP		"mcp2510"

#endif /* _UAPI_LINUX_CAN_MCP2510_H */
