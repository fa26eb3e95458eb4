// SPDX-License-Identifier: GPL-2.0
/*
 * The chip's hardware acceptance filters under /sys/class/net/canX/mcp2510/,
 * in the format the uapi header documents.  Settings are kept here and
 * programmed into the chip on the next open; they may only change while
 * the interface is down, because the chip accepts them only in
 * configuration mode and a running interface must not lose frames to a
 * half-written filter set.
 */
#include <linux/capability.h>
#include <linux/device.h>
#include <linux/netdevice.h>
#include <linux/rtnetlink.h>
#include <linux/sysfs.h>

#include "mcp2510_priv.h"

enum mcp2510_filter_attr_kind {
	MCP2510_ATTR_MASK,
	MCP2510_ATTR_FILTER,
	MCP2510_ATTR_RXM,
	MCP2510_ATTR_ROLLOVER,
};

struct mcp2510_filter_attr {
	struct device_attribute dev_attr;
	enum mcp2510_filter_attr_kind kind;
	unsigned int index;
};

static const struct mcp2510_filter_attr *
to_filter_attr(const struct device_attribute *attr)
{
	return container_of(attr, struct mcp2510_filter_attr, dev_attr);
}

static ssize_t mcp2510_emit_id(char *buf, const struct mcp2510_filter_id *id)
{
	char text[16];

	mcp2510_filter_id_format(id, text);
	return sysfs_emit(buf, "%s\n", text);
}

static ssize_t mcp2510_filter_emit(const struct mcp2510_filters *f,
				   const struct mcp2510_filter_attr *fa,
				   char *buf)
{
	switch (fa->kind) {
	case MCP2510_ATTR_MASK:
		return mcp2510_emit_id(buf, &f->mask[fa->index]);
	case MCP2510_ATTR_FILTER:
		return mcp2510_emit_id(buf, &f->filter[fa->index]);
	case MCP2510_ATTR_RXM:
		return sysfs_emit(buf, "%s\n", mcp2510_rxm_name(f->rxm[fa->index]));
	case MCP2510_ATTR_ROLLOVER:
		return sysfs_emit(buf, "%d\n", f->rollover);
	}
	return -EINVAL;
}

static int mcp2510_rollover_parse(const char *s, size_t len, bool *rollover)
{
	/* Exactly "0" or "1", as documented: nothing else is guessed at. */
	if (len != 1 || (s[0] != '0' && s[0] != '1'))
		return -EINVAL;
	*rollover = s[0] == '1';
	return 0;
}

static int mcp2510_filter_parse(struct mcp2510_filters *f,
				const struct mcp2510_filter_attr *fa,
				const char *s, size_t len)
{
	switch (fa->kind) {
	case MCP2510_ATTR_MASK:
		return mcp2510_filter_id_parse(s, len, &f->mask[fa->index]);
	case MCP2510_ATTR_FILTER:
		return mcp2510_filter_id_parse(s, len, &f->filter[fa->index]);
	case MCP2510_ATTR_RXM:
		return mcp2510_rxm_parse(s, len, &f->rxm[fa->index]);
	case MCP2510_ATTR_ROLLOVER:
		return mcp2510_rollover_parse(s, len, &f->rollover);
	}
	return -EINVAL;
}

/*
 * rtnl orders these files against open.  It is only tried: unregistering
 * the netdev holds rtnl while it waits for sysfs readers to leave.
 */
static ssize_t mcp2510_filter_show(struct device *dev,
				   struct device_attribute *attr, char *buf)
{
	struct mcp2510_priv *priv = netdev_priv(to_net_dev(dev));
	ssize_t ret;

	if (!rtnl_trylock())
		return restart_syscall();
	ret = mcp2510_filter_emit(&priv->filters, to_filter_attr(attr), buf);
	rtnl_unlock();
	return ret;
}

static ssize_t mcp2510_filter_store(struct device *dev,
				    struct device_attribute *attr,
				    const char *buf, size_t count)
{
	struct net_device *ndev = to_net_dev(dev);
	struct mcp2510_priv *priv = netdev_priv(ndev);
	struct mcp2510_filters next;
	size_t len = count;
	int ret;

	if (!capable(CAP_NET_ADMIN))
		return -EPERM;
	if (len && buf[len - 1] == '\n')
		len--;

	if (!rtnl_trylock())
		return restart_syscall();
	if (netif_running(ndev)) {
		ret = -EBUSY;
	} else {
		/* Parse into a copy: bad input leaves the old setting. */
		next = priv->filters;
		ret = mcp2510_filter_parse(&next, to_filter_attr(attr), buf,
					   len);
		if (!ret)
			priv->filters = next;
	}
	rtnl_unlock();
	return ret ? ret : count;
}

#define MCP2510_FILTER_ATTR(_name, _kind, _index)			\
	static struct mcp2510_filter_attr mcp2510_attr_##_name = {	\
		.dev_attr = __ATTR(_name, 0644, mcp2510_filter_show,	\
				   mcp2510_filter_store),		\
		.kind = (_kind),					\
		.index = (_index),					\
	}

MCP2510_FILTER_ATTR(mask0, MCP2510_ATTR_MASK, 0);
MCP2510_FILTER_ATTR(mask1, MCP2510_ATTR_MASK, 1);
MCP2510_FILTER_ATTR(filter0, MCP2510_ATTR_FILTER, 0);
MCP2510_FILTER_ATTR(filter1, MCP2510_ATTR_FILTER, 1);
MCP2510_FILTER_ATTR(filter2, MCP2510_ATTR_FILTER, 2);
MCP2510_FILTER_ATTR(filter3, MCP2510_ATTR_FILTER, 3);
MCP2510_FILTER_ATTR(filter4, MCP2510_ATTR_FILTER, 4);
MCP2510_FILTER_ATTR(filter5, MCP2510_ATTR_FILTER, 5);
MCP2510_FILTER_ATTR(rxm0, MCP2510_ATTR_RXM, 0);
MCP2510_FILTER_ATTR(rxm1, MCP2510_ATTR_RXM, 1);
MCP2510_FILTER_ATTR(rollover, MCP2510_ATTR_ROLLOVER, 0);

static struct attribute *mcp2510_filter_attrs[] = {
	&mcp2510_attr_mask0.dev_attr.attr,
	&mcp2510_attr_mask1.dev_attr.attr,
	&mcp2510_attr_filter0.dev_attr.attr,
	&mcp2510_attr_filter1.dev_attr.attr,
	&mcp2510_attr_filter2.dev_attr.attr,
	&mcp2510_attr_filter3.dev_attr.attr,
	&mcp2510_attr_filter4.dev_attr.attr,
	&mcp2510_attr_filter5.dev_attr.attr,
	&mcp2510_attr_rxm0.dev_attr.attr,
	&mcp2510_attr_rxm1.dev_attr.attr,
	&mcp2510_attr_rollover.dev_attr.attr,
	NULL
};

const struct attribute_group mcp2510_filter_group = {
	.name = MCP2510_SYSFS_GROUP,
	.attrs = mcp2510_filter_attrs,
};
