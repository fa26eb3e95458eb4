// SPDX-License-Identifier: GPL-2.0
/*
 * struct can_frame <-> the SIDH..D7 registers of a transmit or receive
 * buffer.  Offsets below are relative to SIDH, the first byte the
 * MCP2515's buffer instructions transfer.
 *
 * The chip keeps the four DLC bits as written: a DLC of 9..15 goes on the
 * wire as is, with eight data bytes, and a received one is stored as it
 * came.  With CAN_CTRLMODE_CC_LEN8_DLC such a DLC travels in len8_dlc
 * beside a length of 8; without it a sent frame's len8_dlc is ignored and
 * a received DLC above 8 reads as length 8.
 */
#include "mcp2510_core_priv.h"

#define REG(off)	((off) - MCP2510_BUF_SIDH)

static void id_encode(canid_t can_id, u8 *regs)
{
	u32 id;

	if (can_id & CAN_EFF_FLAG) {
		id = can_id & CAN_EFF_MASK;
		regs[0] = id >> (MCP2510_EID_BITS + MCP2510_SID_SHIFT_SIDH);
		regs[1] = ((id >> MCP2510_EID_BITS) << MCP2510_SID_SHIFT_SIDL &
			   MCP2510_SIDL_SID_MASK) |
			  MCP2510_SIDL_EXIDE |
			  ((id >> 16) & MCP2510_SIDL_EID_MASK);
		regs[2] = id >> 8;
		regs[3] = id;
	} else {
		id = can_id & CAN_SFF_MASK;
		regs[0] = id >> MCP2510_SID_SHIFT_SIDH;
		regs[1] = id << MCP2510_SID_SHIFT_SIDL & MCP2510_SIDL_SID_MASK;
		regs[2] = 0;
		regs[3] = 0;
	}
}

int mcp2510_frame_encode(const struct can_frame *cf, u32 ctrlmode, u8 *regs)
{
	bool rtr = cf->can_id & CAN_RTR_FLAG;
	unsigned int ndata = rtr ? 0 : cf->len;

	if (cf->len > CAN_MAX_DLEN)
		return -EINVAL;
	id_encode(cf->can_id, regs);
	regs[REG(MCP2510_BUF_DLC)] = can_get_cc_dlc(cf, ctrlmode) |
				     (rtr ? MCP2510_DLC_RTR : 0);
	memcpy(regs + REG(MCP2510_BUF_D0), cf->data, ndata);
	return REG(MCP2510_BUF_D0) + ndata;
}

void mcp2510_frame_decode(const u8 *regs, u32 ctrlmode, struct can_frame *cf)
{
	u8 sidl = regs[REG(MCP2510_BUF_SIDL)];
	u8 dlc = regs[REG(MCP2510_BUF_DLC)];
	u32 sid = (u32)regs[REG(MCP2510_BUF_SIDH)] << MCP2510_SID_SHIFT_SIDH |
		  (sidl & MCP2510_SIDL_SID_MASK) >> MCP2510_SID_SHIFT_SIDL;
	bool rtr;

	memset(cf, 0, sizeof(*cf));
	if (sidl & MCP2510_SIDL_EXIDE) {
		cf->can_id = CAN_EFF_FLAG | sid << MCP2510_EID_BITS |
			     (u32)(sidl & MCP2510_SIDL_EID_MASK) << 16 |
			     (u32)regs[REG(MCP2510_BUF_EID8)] << 8 |
			     regs[REG(MCP2510_BUF_EID0)];
		/* an extended frame's RTR bit lives in the DLC register */
		rtr = dlc & MCP2510_DLC_RTR;
	} else {
		cf->can_id = sid;
		rtr = sidl & MCP2510_SIDL_SRR;
	}
	/* DLC 9..15 means eight bytes on the wire; never read past D7 */
	can_frame_set_cc_len(cf, dlc & MCP2510_DLC_MASK, ctrlmode);
	if (rtr)
		cf->can_id |= CAN_RTR_FLAG;
	else
		memcpy(cf->data, regs + REG(MCP2510_BUF_D0), cf->len);
}
