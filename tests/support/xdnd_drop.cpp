// xdnd_drop WINDOW X Y PATH...: drops files onto an X11 window as a file manager does, by
// the XDND protocol (freedesktop.org, version 5): XdndEnter offering text/uri-list,
// XdndPosition at (X, Y) in the window, XdndDrop once the target accepts, the URI list handed
// over through the XdndSelection selection, and XdndFinished awaited. The target's own
// toolkit (GLFW for the viewer) does the rest, so a test under Xvfb exercises the same code
// as a person dragging a file from a file manager: xdotool can move the mouse but cannot be
// a drag source.
//
// Exit status: 0 the target accepted and finished the drop; 1 it refused or failed it;
// 2 bad arguments or no display; 3 no answer within 20 seconds.
#include <X11/Xatom.h>
#include <X11/Xlib.h>
#include <poll.h>

#include <algorithm>
#include <cctype>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <string>

namespace {

// file:// URI of an absolute path, bytes outside RFC 3986's unreserved set and '/'
// percent-encoded.
std::string file_uri(const std::string& path) {
  std::string uri = "file://";
  for (unsigned char c : path) {
    const bool plain = std::isalnum(c) || c == '/' || c == '-' || c == '_' || c == '.' || c == '~';
    if (plain) {
      uri += static_cast<char>(c);
    } else {
      char hex[4];
      std::snprintf(hex, sizeof hex, "%%%02X", c);
      uri += hex;
    }
  }
  return uri;
}

struct Atoms {
  Atom aware, enter, position, status, drop, finished, selection, copy, uri_list;
  explicit Atoms(Display* d)
      : aware(XInternAtom(d, "XdndAware", False)),
        enter(XInternAtom(d, "XdndEnter", False)),
        position(XInternAtom(d, "XdndPosition", False)),
        status(XInternAtom(d, "XdndStatus", False)),
        drop(XInternAtom(d, "XdndDrop", False)),
        finished(XInternAtom(d, "XdndFinished", False)),
        selection(XInternAtom(d, "XdndSelection", False)),
        copy(XInternAtom(d, "XdndActionCopy", False)),
        uri_list(XInternAtom(d, "text/uri-list", False)) {}
};

void send(Display* d, Window target, Atom type, long l0, long l1, long l2, long l3, long l4) {
  XEvent e{};
  e.xclient.type = ClientMessage;
  e.xclient.display = d;
  e.xclient.window = target;
  e.xclient.message_type = type;
  e.xclient.format = 32;
  e.xclient.data.l[0] = l0;
  e.xclient.data.l[1] = l1;
  e.xclient.data.l[2] = l2;
  e.xclient.data.l[3] = l3;
  e.xclient.data.l[4] = l4;
  XSendEvent(d, target, False, NoEventMask, &e);
  XFlush(d);
}

// The next event, or false after `deadline`.
bool next_event(Display* d, XEvent& e, std::chrono::steady_clock::time_point deadline) {
  while (XPending(d) == 0) {
    const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(
        deadline - std::chrono::steady_clock::now());
    if (left.count() <= 0) return false;
    pollfd p{ConnectionNumber(d), POLLIN, 0};
    poll(&p, 1, static_cast<int>(std::min<long long>(left.count(), 100)));
  }
  XNextEvent(d, &e);
  return true;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 5) {
    std::fprintf(stderr, "usage: xdnd_drop WINDOW X Y PATH...\n");
    return 2;
  }
  Display* d = XOpenDisplay(nullptr);
  if (d == nullptr) {
    std::fprintf(stderr, "xdnd_drop: no display\n");
    return 2;
  }
  const Atoms atom(d);
  const Window target = std::strtoul(argv[1], nullptr, 0);
  const Window root = DefaultRootWindow(d);
  std::string uris;
  for (int i = 4; i < argc; ++i) uris += file_uri(argv[i]) + "\r\n";

  // The target must say it takes drops, and which protocol version.
  Atom type = None;
  int format = 0;
  unsigned long count = 0, after = 0;
  unsigned char* data = nullptr;
  long version = 0;
  if (XGetWindowProperty(d, target, atom.aware, 0, 1, False, AnyPropertyType, &type, &format,
                         &count, &after, &data) == Success &&
      data != nullptr && count == 1) {
    version = std::min(5L, static_cast<long>(*reinterpret_cast<Atom*>(data)));
  }
  if (data != nullptr) XFree(data);
  if (version < 2) {
    std::fprintf(stderr, "xdnd_drop: window 0x%lx does not accept drops (XdndAware)\n", target);
    return 1;
  }
  int root_x = 0, root_y = 0;
  Window child = None;
  XTranslateCoordinates(d, target, root, std::atoi(argv[2]), std::atoi(argv[3]), &root_x, &root_y,
                        &child);

  const Window source = XCreateSimpleWindow(d, root, 0, 0, 1, 1, 0, 0, 0);
  XSelectInput(d, source, PropertyChangeMask);
  XSetSelectionOwner(d, atom.selection, source, CurrentTime);
  send(d, target, atom.enter, static_cast<long>(source), version << 24,
       static_cast<long>(atom.uri_list), None, None);
  send(d, target, atom.position, static_cast<long>(source), 0, (root_x << 16) | (root_y & 0xffff),
       CurrentTime, static_cast<long>(atom.copy));

  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(20);
  XEvent e;
  bool dropped = false;
  while (next_event(d, e, deadline)) {
    if (e.type == ClientMessage && e.xclient.message_type == atom.status && !dropped) {
      if ((e.xclient.data.l[1] & 1) == 0) {
        send(d, target, XInternAtom(d, "XdndLeave", False), static_cast<long>(source), 0, 0, 0, 0);
        std::fprintf(stderr, "xdnd_drop: the window refused the drop\n");
        return 1;
      }
      send(d, target, atom.drop, static_cast<long>(source), 0, CurrentTime, 0, 0);
      dropped = true;
    } else if (e.type == SelectionRequest) {
      // The target asks for the data: the URI list, written on its property.
      const XSelectionRequestEvent& r = e.xselectionrequest;
      XEvent reply{};
      reply.xselection.type = SelectionNotify;
      reply.xselection.display = d;
      reply.xselection.requestor = r.requestor;
      reply.xselection.selection = r.selection;
      reply.xselection.target = r.target;
      reply.xselection.time = r.time;
      reply.xselection.property = None;
      if (r.target == atom.uri_list) {
        XChangeProperty(d, r.requestor, r.property, atom.uri_list, 8, PropModeReplace,
                        reinterpret_cast<const unsigned char*>(uris.data()),
                        static_cast<int>(uris.size()));
        reply.xselection.property = r.property;
      }
      XSendEvent(d, r.requestor, False, NoEventMask, &reply);
      XFlush(d);
    } else if (e.type == ClientMessage && e.xclient.message_type == atom.finished) {
      // The protocol's flag is bit 0; GLFW 3.3 sends the byte count of the data it read
      // instead (zero when it read nothing), so any nonzero value is taken as accepted.
      const bool accepted = e.xclient.data.l[1] != 0;
      if (!accepted) std::fprintf(stderr, "xdnd_drop: the window did not take the data\n");
      XDestroyWindow(d, source);
      XCloseDisplay(d);
      return accepted ? 0 : 1;
    }
  }
  std::fprintf(stderr, "xdnd_drop: no answer from window 0x%lx within 20 s\n", target);
  return 3;
}
