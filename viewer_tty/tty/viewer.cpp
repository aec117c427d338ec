// SPDX-License-Identifier: MIT
// viewer.cpp — key handling, the status line, and two loops: scripted (deterministic text on any
// stream) and interactive (termios raw mode on /dev/tty, alternate screen, poll with a timeout).
// Signals: SIGWINCH and the terminating signals are caught while the interactive loop runs; the
// handlers touch only the few globals below (async-signal-safe calls only): a resize wakes the
// loop through a self-pipe, a terminating signal restores the terminal and re-raises itself.
#include "viewer_tty/tty/viewer.h"

#include <fcntl.h>
#include <poll.h>
#include <sys/ioctl.h>
#include <termios.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <csignal>
#include <deque>
#include <sstream>

#include "viewer_tty/tty/halfblock.h"

namespace pem::tty {

namespace {

constexpr double kAngleStep = 5.0, kMaxAngle = 85.0, kZoomStep = 0.9;
constexpr double kMinDistance = 0.2, kMaxDistance = 10.0, kMinT = 1.0, kMaxT = 64.0;
constexpr int kMaxCsiLength = 16;  // longer "sequences" are garbage: back to ground

double WrapDegrees(double deg) {
    const double wrapped = std::fmod(deg, 360.0);
    return wrapped < 0.0 ? wrapped + 360.0 : wrapped;
}

// The arrow key of the final byte A..D of ESC [ A or ESC O A, else -1.
int ArrowKey(unsigned char final) {
    constexpr int kArrows[] = {kKeyUp, kKeyDown, kKeyRight, kKeyLeft};
    return final >= 'A' && final <= 'D' ? kArrows[final - 'A'] : -1;
}

std::string Format(const char* format, double value) {
    char buf[64];
    std::snprintf(buf, sizeof buf, format, value);
    return buf;
}

}  // namespace

// View state ---------------------------------------------------------------------------------

const char* ToString(ViewMode mode) {
    constexpr const char* kNames[kNumViewModes] = {"hybrid", "pem", "static-em", "ray-traced",
                                                   "difference"};
    const int index = static_cast<int>(mode);
    return index >= 0 && index < kNumViewModes ? kNames[index] : "?";
}

std::string ToString(const ViewState& s) {
    std::ostringstream os;
    os << "ViewState{" << ToString(s.mode) << " az " << s.azimuthDeg << " el " << s.elevationDeg
       << " dist " << s.distanceScale << " off " << s.heightOffsetDeg << " t " << s.t
       << (s.quit ? " quit}" : "}");
    return os.str();
}

std::ostream& operator<<(std::ostream& os, const ViewState& state) {
    return os << ToString(state);
}

namespace {

// The camera keys: azimuth (wraps), elevation and height offset (clamped), distance (clamped).
void MoveCamera(ViewState* state, int key) {
    ViewState& s = *state;
    const auto clampAngle = [](double deg) { return std::clamp(deg, -kMaxAngle, kMaxAngle); };
    const auto clampDistance = [](double d) { return std::clamp(d, kMinDistance, kMaxDistance); };
    switch (key) {
        case kKeyLeft:
        case 'h':
            s.azimuthDeg = WrapDegrees(s.azimuthDeg - kAngleStep);
            break;
        case kKeyRight:
        case 'l':
            s.azimuthDeg = WrapDegrees(s.azimuthDeg + kAngleStep);
            break;
        case kKeyUp:
        case 'k':
            s.elevationDeg = clampAngle(s.elevationDeg + kAngleStep);
            break;
        case kKeyDown:
        case 'j':
            s.elevationDeg = clampAngle(s.elevationDeg - kAngleStep);
            break;
        case 'u':
            s.heightOffsetDeg = clampAngle(s.heightOffsetDeg + kAngleStep);
            break;
        case 'd':
            s.heightOffsetDeg = clampAngle(s.heightOffsetDeg - kAngleStep);
            break;
        case '+':
        case '=':
            s.distanceScale = clampDistance(s.distanceScale * kZoomStep);
            break;
        case '-':
        case '_':
            s.distanceScale = clampDistance(s.distanceScale / kZoomStep);
            break;
        default:
            break;
    }
}

}  // namespace

bool ApplyKey(ViewState* state, int key, const ViewState& home) {
    const ViewState before = *state;
    ViewState& s = *state;
    MoveCamera(state, key);
    if (key >= '1' && key < '1' + kNumViewModes) s.mode = static_cast<ViewMode>(key - '1');
    if (key == 'm') s.mode = static_cast<ViewMode>((static_cast<int>(s.mode) + 1) % kNumViewModes);
    if (key == '[') s.t = std::clamp(s.t - 1.0, kMinT, kMaxT);
    if (key == ']') s.t = std::clamp(s.t + 1.0, kMinT, kMaxT);
    if (key == 'r') {  // back to `home`, in the current mode
        const ViewMode mode = s.mode;
        s = home;
        s.mode = mode;
        s.quit = false;
    }
    if (key == 'q' || key == kKeyEscape || key == kKeyCtrlC) s.quit = true;
    return !(s == before);
}

// Keys ---------------------------------------------------------------------------------------

std::vector<int> KeyDecoder::Feed(std::string_view bytes) {
    std::vector<int> keys;
    for (char c : bytes) Step(static_cast<unsigned char>(c), &keys);
    return keys;
}

std::vector<int> KeyDecoder::Flush() {
    std::vector<int> keys;
    if (state_ == State::Escape) keys.push_back(kKeyEscape);  // a lone ESC: the Escape key
    state_ = State::Ground;                                   // a cut-off sequence: dropped
    return keys;
}

void KeyDecoder::Step(unsigned char byte, std::vector<int>* keys) {
    switch (state_) {
        case State::Ground:
            if (byte == kKeyEscape)
                state_ = State::Escape;
            else
                keys->push_back(byte);
            return;
        case State::Escape:
            // Step 1: ESC [ starts a CSI sequence, ESC O an SS3 one; anything else was Escape.
            if (byte == '[') {
                state_ = State::Csi;
                csiLength_ = 0;
                return;
            }
            if (byte == 'O') {
                state_ = State::Ss3;
                return;
            }
            keys->push_back(kKeyEscape);
            state_ = State::Ground;
            Step(byte, keys);
            return;
        case State::Csi:
            // Step 2: parameter and intermediate bytes (0x20..0x3F), then one final byte.
            if (byte >= 0x20 && byte <= 0x3F && ++csiLength_ <= kMaxCsiLength) return;
            state_ = State::Ground;
            if (byte >= 0x40 && byte <= 0x7E) {
                if (ArrowKey(byte) >= 0) keys->push_back(ArrowKey(byte));
            } else {
                Step(byte, keys);  // not a sequence after all: the byte is a key of its own
            }
            return;
        case State::Ss3:
            state_ = State::Ground;
            if (ArrowKey(byte) >= 0) keys->push_back(ArrowKey(byte));
            return;
    }
}

std::vector<int> DecodeKeys(std::string_view bytes) {
    KeyDecoder decoder;
    std::vector<int> keys = decoder.Feed(bytes);
    const std::vector<int> rest = decoder.Flush();
    keys.insert(keys.end(), rest.begin(), rest.end());
    return keys;
}

// Frames -------------------------------------------------------------------------------------

std::string StatusLine(const ViewState& s, double fps, std::string_view info, int maxColumns) {
    const char* deg = "\xc2\xb0";
    std::string line = std::string(ToString(s.mode)) + " az " + Format("%.4g", s.azimuthDeg) + deg +
                       " el " + Format("%.3g", s.elevationDeg) + deg + " dist " +
                       Format("%.3g", s.distanceScale) + " off " +
                       Format("%.3g", s.heightOffsetDeg) + deg + " t " + Format("%g", s.t);
    if (fps >= 0.0) line += " | " + Format(fps < 10.0 ? "%.1f" : "%.0f", fps) + " fps";
    if (!info.empty()) line += " | " + std::string(info);
    // Control characters would move the cursor; a code point counts as one column.
    std::string out;
    int columns = 0;
    for (char c : line) {
        const auto byte = static_cast<unsigned char>(c);
        const bool starts = (byte & 0xC0) != 0x80;
        if (starts && columns++ >= maxColumns) break;
        out += byte < 0x20 || byte == 0x7F ? ' ' : c;
    }
    return out;
}

namespace {

struct Screen {
    int cols = 80, rows = 24;
    int ImageRows() const { return rows - 1; }
};

Screen ClampScreen(int cols, int rows) {
    return {std::max(cols, 1), std::max(rows, 2)};
}

// The image as exactly ImageRows() lines of half blocks (empty lines for an empty image).
std::vector<std::string> ImageLines(const base::Image8& image, Screen screen) {
    std::vector<std::string> lines;
    const std::string text = HalfBlockFrame(image, screen.cols, screen.ImageRows());
    for (size_t at = 0; at < text.size();) {
        const size_t end = std::min(text.find('\n', at), text.size());
        lines.push_back(text.substr(at, end - at));
        at = end + 1;
    }
    lines.resize(static_cast<size_t>(screen.ImageRows()));
    return lines;
}

ViewFrame RenderFor(const RenderViewFn& render, const ViewState& state, Screen screen) {
    return render(state, screen.cols, 2 * screen.ImageRows());
}

int RunScripted(const ViewerOptions& options, ViewState initial, const RenderViewFn& render,
                std::FILE* out) {
    const std::vector<int> keys = DecodeKeys(options.keys);
    const Screen screen =
        ClampScreen(options.cols > 0 ? options.cols : 80, options.rows > 0 ? options.rows : 24);
    const size_t nFrames =
        options.frames > 0 ? static_cast<size_t>(options.frames) : keys.size() + 1;
    ViewState state = initial;
    for (size_t n = 0; n < nFrames; ++n) {
        // Step 1: frame n shows the state after the n-th key (the last state once keys run out).
        if (n > 0 && n <= keys.size()) ApplyKey(&state, keys[n - 1], initial);
        if (state.quit) break;
        // Step 2: separator, image lines, status line (no FPS: the text is deterministic).
        const ViewFrame frame = RenderFor(render, state, screen);
        std::string text = "--- frame " + std::to_string(n) + " ---\n";
        if (!options.quiet) {
            for (const std::string& line : ImageLines(frame.image, screen)) text += line + "\n";
        }
        text += StatusLine(state, -1.0, frame.info, screen.cols) + "\n";
        std::fputs(text.c_str(), out);
    }
    std::fflush(out);
    return 0;
}

// Interactive terminal -----------------------------------------------------------------------

// Globals for the signal handlers (one interactive session at a time).
int gTtyFd = -1, gOutFd = -1;
int gWakePipe[2] = {-1, -1};
termios gSavedTermios{};
volatile std::sig_atomic_t gResized = 0;

constexpr char kEnterScreen[] = "\x1b[?1049h\x1b[?25l\x1b[2J";  // alternate screen, no cursor
constexpr char kLeaveScreen[] = "\x1b[0m\x1b[?25h\x1b[?1049l";
constexpr int kHandledSignals[] = {SIGINT, SIGTERM, SIGHUP, SIGQUIT, SIGWINCH};

void WriteAll(int fd, const char* text, size_t size) {
    while (size > 0) {
        const ssize_t n = write(fd, text, size);
        if (n <= 0) return;
        text += n;
        size -= static_cast<size_t>(n);
    }
}

extern "C" void OnSignal(int sig) {
    if (sig == SIGWINCH) {
        gResized = 1;
        const char wake = 'w';
        WriteAll(gWakePipe[1], &wake, 1);
        return;
    }
    // A terminating signal: restore the terminal, then die of the same signal.
    WriteAll(gOutFd, kLeaveScreen, sizeof kLeaveScreen - 1);
    tcsetattr(gTtyFd, TCSAFLUSH, &gSavedTermios);
    std::signal(sig, SIG_DFL);
    std::raise(sig);
}

// Raw mode, alternate screen and signal handlers for its lifetime (restored by the destructor,
// also when an exception unwinds).
class TerminalSession {
  public:
    explicit TerminalSession(std::FILE* out) : out_(out) {
        if (isatty(fileno(out)) != 1) return;
        fd_ = open("/dev/tty", O_RDWR | O_NOCTTY | O_CLOEXEC);
        if (fd_ < 0 || tcgetattr(fd_, &gSavedTermios) != 0) return;
        if (pipe2(gWakePipe, O_CLOEXEC | O_NONBLOCK) != 0) return;
        gTtyFd = fd_;
        gOutFd = fileno(out);
        // Step 1: raw input (no echo, no line editing, Ctrl-C as a byte), output untouched.
        termios raw = gSavedTermios;
        raw.c_lflag &= ~static_cast<tcflag_t>(ICANON | ECHO | ISIG | IEXTEN);
        raw.c_iflag &= ~static_cast<tcflag_t>(IXON | ICRNL | BRKINT | ISTRIP | INPCK);
        raw.c_cc[VMIN] = 0;
        raw.c_cc[VTIME] = 0;
        tcsetattr(fd_, TCSAFLUSH, &raw);
        // Step 2: signal handlers, then the alternate screen.
        struct sigaction action {};
        action.sa_handler = OnSignal;
        sigemptyset(&action.sa_mask);
        for (size_t i = 0; i < std::size(kHandledSignals); ++i)
            sigaction(kHandledSignals[i], &action, &oldActions_[i]);
        Write(kEnterScreen);
        ok_ = true;
    }
    ~TerminalSession() {
        if (ok_) {
            Write(kLeaveScreen);
            tcsetattr(fd_, TCSAFLUSH, &gSavedTermios);
            for (size_t i = 0; i < std::size(kHandledSignals); ++i)
                sigaction(kHandledSignals[i], &oldActions_[i], nullptr);
        }
        for (int& p : gWakePipe) {
            if (p >= 0) close(p);
            p = -1;
        }
        if (fd_ >= 0) close(fd_);
        gTtyFd = gOutFd = -1;
    }
    TerminalSession(const TerminalSession&) = delete;
    TerminalSession& operator=(const TerminalSession&) = delete;

    bool Ok() const { return ok_; }
    void Write(const std::string& text) {
        std::fwrite(text.data(), 1, text.size(), out_);
        std::fflush(out_);
    }
    TermSize Size() const {
        winsize ws{};
        if (ioctl(fd_, TIOCGWINSZ, &ws) == 0 && ws.ws_col > 0 && ws.ws_row > 0)
            return {ws.ws_col, ws.ws_row};
        return TerminalSize();
    }
    // Waits up to timeoutMs for input or a signal; "" on a timeout or a signal. Sets *hangup
    // when the terminal went away.
    std::string Read(int timeoutMs, bool* hangup) {
        pollfd fds[2] = {{fd_, POLLIN, 0}, {gWakePipe[0], POLLIN, 0}};
        if (poll(fds, 2, timeoutMs) <= 0) return "";
        char buf[256];
        if (fds[1].revents & POLLIN) {
            while (read(gWakePipe[0], buf, sizeof buf) > 0) {
            }
        }
        if (fds[0].revents & (POLLHUP | POLLERR | POLLNVAL)) *hangup = true;
        if (!(fds[0].revents & POLLIN)) return "";
        const ssize_t n = read(fd_, buf, sizeof buf);
        if (n <= 0) return "";
        return std::string(buf, static_cast<size_t>(n));
    }

  private:
    std::FILE* out_;
    int fd_ = -1;
    bool ok_ = false;
    struct sigaction oldActions_[std::size(kHandledSignals)]{};
};

// Frames per second over the last few frames (render + print time).
class FpsMeter {
  public:
    void Add(double seconds) {
        times_.push_back(seconds);
        if (times_.size() > 10) times_.pop_front();
    }
    double Fps() const {
        double sum = 0.0;
        for (double t : times_) sum += t;
        return times_.empty() || sum <= 0.0 ? -1.0 : static_cast<double>(times_.size()) / sum;
    }

  private:
    std::deque<double> times_;
};

// One full screen: image rows by absolute cursor positions (no scrolling), then the status line.
std::string ScreenText(const ViewFrame& frame, const ViewState& state, double fps, Screen screen,
                       bool clear) {
    std::string text = clear ? "\x1b[0m\x1b[2J" : "";
    const std::vector<std::string> lines = ImageLines(frame.image, screen);
    for (size_t i = 0; i < lines.size(); ++i)
        text += "\x1b[" + std::to_string(i + 1) + ";1H" + lines[i] + "\x1b[0m\x1b[K";
    text += "\x1b[" + std::to_string(screen.rows) + ";1H\x1b[0m";
    text += StatusLine(state, fps, frame.info, screen.cols - 1) + "\x1b[K";
    return text;
}

int RunInteractive(TerminalSession* session, const ViewerOptions& options, ViewState initial,
                   const RenderViewFn& render) {
    using Clock = std::chrono::steady_clock;
    const auto querySize = [&] {
        const TermSize size = session->Size();
        return ClampScreen(options.cols > 0 ? options.cols : size.cols,
                           options.rows > 0 ? options.rows : size.rows);
    };
    Screen screen = querySize();
    ViewState state = initial;
    KeyDecoder decoder;
    FpsMeter fps;
    bool dirty = true, clear = false, hangup = false;
    while (!state.quit && !hangup) {
        // Step 1: a resize re-queries the size and redraws everything.
        if (gResized) {
            gResized = 0;
            screen = querySize();
            dirty = clear = true;
        }
        // Step 2: redraw only when something changed; time render + print.
        if (dirty) {
            const Clock::time_point start = Clock::now();
            const ViewFrame frame = RenderFor(render, state, screen);
            session->Write(ScreenText(frame, state, fps.Fps(), screen, clear));
            fps.Add(std::chrono::duration<double>(Clock::now() - start).count());
            dirty = clear = false;
        }
        // Step 3: wait for keys; a lone ESC becomes the Escape key after 30 ms of silence.
        const std::string bytes = session->Read(decoder.Pending() ? 30 : 250, &hangup);
        const std::vector<int> keys =
            bytes.empty() ? (decoder.Pending() ? decoder.Flush() : std::vector<int>{})
                          : decoder.Feed(bytes);
        for (int key : keys) dirty = ApplyKey(&state, key, initial) || dirty;
    }
    return 0;
}

}  // namespace

int RunViewer(const ViewerOptions& options, ViewState initial, const RenderViewFn& render,
              std::FILE* out) {
    if (!options.keys.empty() || options.frames > 0)
        return RunScripted(options, initial, render, out);
    TerminalSession session(out);
    if (!session.Ok()) {
        std::fputs("pemref view: not a terminal (use --keys/--frames)\n", stderr);
        return 2;
    }
    return RunInteractive(&session, options, initial, render);
}

}  // namespace pem::tty
