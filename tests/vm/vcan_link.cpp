// SPDX-License-Identifier: MIT
// jacobid-vcan-link: creates (or deletes) a vcan interface through rtnetlink, like
// `ip link add dev NAME [mtu N] type vcan && ip link set NAME up`, for initramfs images whose busybox
// `ip` cannot create vcan links. Static, no dependencies; needs CAP_NET_ADMIN and the vcan module.
//   jacobid-vcan-link add vcan0            classic CAN (MTU 16)
//   jacobid-vcan-link add vcan1 --mtu 72   CAN FD
//   jacobid-vcan-link del vcan0
#include <linux/if.h>
#include <linux/if_link.h>
#include <linux/netlink.h>
#include <linux/rtnetlink.h>
#include <sys/socket.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>

namespace {

struct Request {
    nlmsghdr header;
    ifinfomsg info;
    char attributes[256];
};

rtattr* add_attribute(nlmsghdr* h, unsigned short type, const void* data, std::size_t len) {
    auto* a = reinterpret_cast<rtattr*>(reinterpret_cast<char*>(h) + NLMSG_ALIGN(h->nlmsg_len));
    a->rta_type = type;
    a->rta_len = static_cast<unsigned short>(RTA_LENGTH(len));
    if (len) std::memcpy(RTA_DATA(a), data, len);
    h->nlmsg_len = NLMSG_ALIGN(h->nlmsg_len) + RTA_ALIGN(a->rta_len);
    return a;
}

int talk(Request& req) {
    const int fd = ::socket(AF_NETLINK, SOCK_RAW | SOCK_CLOEXEC, NETLINK_ROUTE);
    if (fd < 0) return errno;
    sockaddr_nl kernel{};
    kernel.nl_family = AF_NETLINK;
    int result = 0;
    if (::sendto(fd, &req, req.header.nlmsg_len, 0, reinterpret_cast<sockaddr*>(&kernel), sizeof kernel) < 0) {
        result = errno;
    } else {
        char buf[4096];
        const ssize_t n = ::recv(fd, buf, sizeof buf, 0);
        if (n < 0) {
            result = errno;
        } else {
            auto* h = reinterpret_cast<nlmsghdr*>(buf);
            if (h->nlmsg_type == NLMSG_ERROR) result = -static_cast<nlmsgerr*>(NLMSG_DATA(h))->error;
        }
    }
    ::close(fd);
    return result;
}

int usage() {
    std::fprintf(stderr, "usage: jacobid-vcan-link add NAME [--mtu 16|72] | del NAME\n");
    return 2;
}

}  // namespace

int main(int argc, char** argv) {
    if (argc < 3) return usage();
    const std::string op = argv[1];
    const char* name = argv[2];
    if (std::strlen(name) >= IFNAMSIZ) return usage();
    unsigned mtu = 0;
    for (int i = 3; i < argc; ++i) {
        if (std::strcmp(argv[i], "--mtu") == 0 && i + 1 < argc) mtu = static_cast<unsigned>(std::atoi(argv[++i]));
        else return usage();
    }
    Request req{};
    req.header.nlmsg_len = NLMSG_LENGTH(sizeof(ifinfomsg));
    req.header.nlmsg_seq = 1;
    req.info.ifi_family = AF_UNSPEC;
    add_attribute(&req.header, IFLA_IFNAME, name, std::strlen(name) + 1);
    if (op == "add") {
        req.header.nlmsg_type = RTM_NEWLINK;
        req.header.nlmsg_flags = NLM_F_REQUEST | NLM_F_ACK | NLM_F_CREATE | NLM_F_EXCL;
        req.info.ifi_flags = IFF_UP;
        req.info.ifi_change = IFF_UP;
        if (mtu) add_attribute(&req.header, IFLA_MTU, &mtu, sizeof mtu);
        rtattr* linkinfo = add_attribute(&req.header, IFLA_LINKINFO, nullptr, 0);
        add_attribute(&req.header, IFLA_INFO_KIND, "vcan", 4);
        linkinfo->rta_len = static_cast<unsigned short>(reinterpret_cast<char*>(&req) + req.header.nlmsg_len -
                                                        reinterpret_cast<char*>(linkinfo));
    } else if (op == "del") {
        req.header.nlmsg_type = RTM_DELLINK;
        req.header.nlmsg_flags = NLM_F_REQUEST | NLM_F_ACK;
    } else {
        return usage();
    }
    const int err = talk(req);
    if (err != 0) {
        std::fprintf(stderr, "jacobid-vcan-link: %s %s: %s%s\n", op.c_str(), name, std::strerror(err),
                     err == EOPNOTSUPP ? " (vcan module not loaded?)" : "");
        return 1;
    }
    std::printf("jacobid-vcan-link: %s %s%s\n", op == "add" ? "created" : "deleted", name,
                mtu ? (" mtu " + std::to_string(mtu)).c_str() : "");
    return 0;
}
