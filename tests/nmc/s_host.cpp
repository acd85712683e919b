// S-HOST-C++ (digest 001 §5, C4): a C++ host program as the manual's Visual C++ example writes
// it: NMC_DevSearch(Ethernet, &n, list) -> NMC_DevOpen -> NMC_MtOpen -> NMC_MtSetSvOn, here in a
// small RAII class, with the I/O calls of rows 0x12xx on top. Compiled with g++ -Wall -Wextra
// -Werror against the headers.
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <stdexcept>
#include <string>
#include <vector>

#include "mtn_lib20.h"

namespace {

void check(short rc, const char *what) {
    if (rc != 0) {
        char desc[256] = {0};
        NMC_GetErrDesc(rc, desc);
        throw std::runtime_error(std::string(what) + " returned " + std::to_string(rc) + ": " + desc);
    }
}

class Controller {
public:
    explicit Controller(short devNo) { check(NMC_DevOpen(devNo, &dev_), "NMC_DevOpen"); }
    Controller(const Controller &) = delete;
    Controller &operator=(const Controller &) = delete;
    ~Controller() {
        for (HAND ax : axes_) NMC_MtSetSvOff(ax);
    }

    HAND axis(short n) {
        HAND ax = 0;
        check(NMC_MtOpen(dev_, n, &ax), "NMC_MtOpen");
        check(NMC_MtSetSvOn(ax), "NMC_MtSetSvOn");
        axes_.push_back(ax);
        return ax;
    }

    std::string id() const {
        char buf[32] = {0};
        check(NMC_DevReadID(dev_, buf), "NMC_DevReadID");
        return buf;
    }

    long di(short group) const {
        long v = 0;
        check(NMC_GetDI(dev_, &v, group), "NMC_GetDI");
        return v;
    }

    HAND handle() const { return dev_; }

private:
    HAND dev_ = 0;
    std::vector<HAND> axes_;
};

}  // namespace

int main() {
    try {
        unsigned short count = 0;
        std::vector<TDevInfo> list(16);
        check(NMC_DevSearch(Ethernet, &count, list.data()), "NMC_DevSearch");
        if (count < 1) throw std::runtime_error("no controller found");
        list.resize(count);
        if (std::string(list[0].idStr) != "CARD1")
            throw std::runtime_error(std::string("first controller is ") + list[0].idStr);

        Controller gcn(0);
        if (gcn.id() != "CARD1") throw std::runtime_error("ID " + gcn.id());
        HAND x = gcn.axis(0);
        short sts = 0;
        for (int polls = 0; !(sts & BIT_AXIS_SVON); ++polls) {
            check(NMC_MtGetSts(x, &sts), "NMC_MtGetSts");
            if (polls > 100000) throw std::runtime_error("servo never on");
        }
        long enable = 0;
        check(NMC_GetDOEx(gcn.handle(), DO_TYPE_MOTOR_ENABLE, 0, &enable), "NMC_GetDOEx");
        if (!(enable & 1)) throw std::runtime_error("enable DO of axis 0 is off");
        long group = 0;
        check(NMC_GetDIGroup(gcn.handle(), &group, 0), "NMC_GetDIGroup");
        if (gcn.di(0) != group) throw std::runtime_error("NMC_GetDI differs from NMC_GetDIGroup");
        HAND none = 0;
        if (NMC_MtOpen(gcn.handle(), 4, &none) != RTN_ARG_RANGE) throw std::runtime_error("axis 4 opened");
    } catch (const std::exception &e) {
        std::fprintf(stderr, "S-HOST-C++: %s\n", e.what());
        return 1;
    }
    std::printf("ok\n");
    return 0;
}
