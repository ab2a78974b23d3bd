// The pictures' text, drawn with FreeType in DejaVu Sans (report/detail/canvas.h).
// note: OpenImageIO 2.4's render_text decodes UTF-8 with an uninitialised code point, so a
// multi-byte character kept the low 6 bits of its last byte ("°" was drawn as "0", "−" as a
// missing-glyph box); its text_size measured the same wrong glyphs. FreeType is what OIIO
// draws with underneath, so the glyphs and their metrics are the same for ASCII.
#include "report/detail/canvas.h"

#include <ft2build.h>
#include FT_FREETYPE_H

#include <algorithm>
#include <filesystem>
#include <vector>

namespace glint::detail {

namespace {

// note: DejaVu comes with fonts-dejavu-core (tools/setup installs it).
const std::string& font_path() {
    static const std::string path = [] {
        for (const char* c : {"/usr/share/fonts/truetype/dejavu/DejaVuSans.ttf"})
            if (std::filesystem::exists(c)) return std::string(c);
        return std::string();
    }();
    return path;
}

// One FreeType library and face per thread: FreeType's objects are not shared across threads,
// and pictures are painted on every worker (report/detail/picture_batches.h).
class FontFace {
  public:
    FontFace() {
        if (font_path().empty() || FT_Init_FreeType(&library_) != 0) return;
        if (FT_New_Face(library_, font_path().c_str(), 0, &face_) != 0) face_ = nullptr;
    }
    ~FontFace() {
        if (face_ != nullptr) FT_Done_Face(face_);
        if (library_ != nullptr) FT_Done_FreeType(library_);
    }
    FontFace(const FontFace&) = delete;
    FontFace& operator=(const FontFace&) = delete;
    [[nodiscard]] FT_Face get() const { return face_; }

  private:
    FT_Library library_ = nullptr;
    FT_Face face_ = nullptr;
};

FT_Face face() {
    thread_local const FontFace f;
    return f.get();
}

// The text's coverage (0…1) over its ink box, which is given relative to the pen's start on
// the baseline (x right, y down).
struct Ink {
    int x0 = 0, y0 = 0, x1 = 0, y1 = 0;
    std::vector<float> alpha;  // (x1 − x0) × (y1 − y0), row-major
    [[nodiscard]] int width() const { return x1 - x0; }
    [[nodiscard]] int height() const { return y1 - y0; }
};

struct PlacedGlyph {
    int left = 0, top = 0, width = 0, rows = 0;
    std::vector<unsigned char> coverage;
};

Ink ink_of(std::string_view text, int size) {
    Ink ink;
    FT_Face f = face();
    if (f == nullptr || text.empty() || FT_Set_Pixel_Sizes(f, 0, static_cast<FT_UInt>(size)) != 0)
        return ink;
    std::vector<PlacedGlyph> glyphs;
    int pen = 0;
    bool any = false;
    for (const char32_t c : decode_utf8(text)) {
        if (FT_Load_Char(f, c, FT_LOAD_RENDER) != 0) continue;
        const FT_GlyphSlot g = f->glyph;
        PlacedGlyph p{.left = pen + g->bitmap_left,
                      .top = -g->bitmap_top,
                      .width = static_cast<int>(g->bitmap.width),
                      .rows = static_cast<int>(g->bitmap.rows)};
        for (int r = 0; r < p.rows; ++r) {
            const unsigned char* row = g->bitmap.buffer + r * g->bitmap.pitch;
            p.coverage.insert(p.coverage.end(), row, row + p.width);
        }
        pen += static_cast<int>(g->advance.x >> 6);
        if (p.width == 0 || p.rows == 0) continue;  // a space
        ink.x0 = any ? std::min(ink.x0, p.left) : p.left;
        ink.y0 = any ? std::min(ink.y0, p.top) : p.top;
        ink.x1 = any ? std::max(ink.x1, p.left + p.width) : p.left + p.width;
        ink.y1 = any ? std::max(ink.y1, p.top + p.rows) : p.top + p.rows;
        any = true;
        glyphs.push_back(std::move(p));
    }
    ink.alpha.assign(static_cast<std::size_t>(ink.width()) * ink.height(), 0.0f);
    for (const auto& p : glyphs)
        for (int r = 0; r < p.rows; ++r)
            for (int i = 0; i < p.width; ++i) {
                float& a = ink.alpha[static_cast<std::size_t>((p.top + r - ink.y0) * ink.width() +
                                                              p.left + i - ink.x0)];
                a = std::max(a, p.coverage[static_cast<std::size_t>(r * p.width + i)] / 255.0f);
            }
    return ink;
}

// The ink grown by `radius` pixels (a square neighbourhood's maximum): the halo under the text.
Ink grown(const Ink& ink, int radius) {
    Ink out{ink.x0 - radius, ink.y0 - radius, ink.x1 + radius, ink.y1 + radius, {}};
    out.alpha.assign(static_cast<std::size_t>(out.width()) * out.height(), 0.0f);
    for (int y = 0; y < ink.height(); ++y)
        for (int x = 0; x < ink.width(); ++x) {
            const float a = ink.alpha[static_cast<std::size_t>(y * ink.width() + x)];
            if (a <= 0.0f) continue;
            for (int dy = 0; dy <= 2 * radius; ++dy)
                for (int dx = 0; dx <= 2 * radius; ++dx) {
                    float& o = out.alpha[static_cast<std::size_t>((y + dy) * out.width() + x + dx)];
                    o = std::max(o, a);
                }
        }
    return out;
}

// Blends `colour` over dst with the ink's coverage, the pen's start at (x, y).
void blend(Canvas& dst, int x, int y, const Ink& ink, const Rgb& colour) {
    const int w = ink.width();
    for (int row = 0; row < ink.height(); ++row)
        for (int col = 0; col < w; ++col) {
            const float a = ink.alpha[static_cast<std::size_t>(row * w + col)];
            const int px = x + ink.x0 + col, py = y + ink.y0 + row;
            if (a <= 0.0f || !dst.contains(px, py)) continue;
            Rgb c = dst.rgb(px, py);
            for (std::size_t k = 0; k < 3; ++k) c[k] += a * (colour[k] - c[k]);
            dst.set(px, py, c);
        }
}

}  // namespace

namespace {

// The number of continuation bytes after a lead byte, -1 for a byte no sequence starts with.
int continuation_bytes(unsigned char lead) {
    if (lead < 0x80) return 0;
    if ((lead & 0xE0) == 0xC0) return 1;
    if ((lead & 0xF0) == 0xE0) return 2;
    if ((lead & 0xF8) == 0xF0) return 3;
    return -1;
}

}  // namespace

std::u32string decode_utf8(std::string_view text) {
    std::u32string out;
    std::size_t i = 0;
    while (i < text.size()) {
        const auto lead = static_cast<unsigned char>(text[i]);
        const int extra = continuation_bytes(lead);
        bool valid = extra >= 0 && i + static_cast<std::size_t>(extra) < text.size();
        // the lead byte's payload: 7, 5, 4 or 3 bits
        auto c = static_cast<char32_t>(lead & (extra == 0 ? 0x7F : 0x3F >> extra));
        for (int k = 1; valid && k <= extra; ++k) {
            const auto b = static_cast<unsigned char>(text[i + static_cast<std::size_t>(k)]);
            valid = (b & 0xC0) == 0x80;
            c = (c << 6) | (b & 0x3F);
        }
        out.push_back(valid ? c : U'\uFFFD');
        i += valid ? static_cast<std::size_t>(extra) + 1 : 1;
    }
    return out;
}

bool has_font() { return face() != nullptr; }

bool font_has_glyph(char32_t c) { return face() != nullptr && FT_Get_Char_Index(face(), c) != 0; }

void draw_text(Canvas& dst, int x, int y, std::string_view text, int size, Rgb colour,
               TextAlign align, int shadow) {
    const Ink ink = ink_of(text, size);
    if (ink.alpha.empty()) return;
    const int left = align == TextAlign::Center  ? x - ink.width() / 2
                     : align == TextAlign::Right ? x - ink.width()
                                                 : x;
    // Text that does not fit whole is left out: a cut word misreads.
    if (left + ink.x0 - shadow < 0 || left + ink.x1 + shadow > dst.width() ||
        y + ink.y0 - shadow < 0 || y + ink.y1 + shadow > dst.height())
        return;
    if (shadow > 0) blend(dst, left, y, grown(ink, shadow), {0.0f, 0.0f, 0.0f});
    blend(dst, left, y, ink, colour);
}

std::string fit_text(const std::string& text, int size, int max_width) {
    if (text_width(text, size) <= max_width) return text;
    for (std::size_t cut = text.rfind(' '); cut != std::string::npos && cut > 0;
         cut = text.rfind(' ', cut - 1)) {
        std::string start = text.substr(0, cut);
        // a parenthesis is not left open: its whole part goes
        const auto open = start.rfind('(');
        if (open != std::string::npos && start.find(')', open) == std::string::npos) continue;
        while (!start.empty() && (start.back() == ',' || start.back() == ':')) start.pop_back();
        if (text_width(start + "\u2026", size) <= max_width) return start + "\u2026";
    }
    return {};
}

std::vector<std::string> wrap_text(const std::string& text, int size, int max_width,
                                   int next_width) {
    std::vector<std::string> lines;
    std::string rest = text;
    while (!rest.empty()) {
        const int width = lines.empty() ? max_width : next_width;
        if (text_width(rest, size) <= width) {
            lines.push_back(rest);
            break;
        }
        std::size_t cut = std::string::npos;
        if (const auto paren = rest.rfind(" ("); paren != std::string::npos && paren > 0 &&
                                                 text_width(rest.substr(0, paren), size) <= width)
            cut = paren;
        for (std::size_t at = rest.rfind(' ');
             cut == std::string::npos && at != std::string::npos && at > 0;
             at = rest.rfind(' ', at - 1))
            if (text_width(rest.substr(0, at), size) <= width) cut = at;
        if (cut == std::string::npos) {  // one word wider than the line
            const auto space = rest.find(' ');
            std::string word = rest.substr(0, space);
            std::string shown = fit_text(word, size, width);
            while (shown.empty() && word.size() > 1) {
                while (word.size() > 1 && (static_cast<unsigned char>(word.back()) & 0xC0) == 0x80)
                    word.pop_back();  // a UTF-8 character is dropped whole
                word.pop_back();
                if (text_width(word + "\u2026", size) <= width) shown = word + "\u2026";
            }
            lines.push_back(shown.empty() ? "\u2026" : shown);
            if (space == std::string::npos) break;
            cut = space;
        } else {
            lines.push_back(rest.substr(0, cut));
        }
        rest = rest.substr(cut + 1);
    }
    return lines;
}

int text_width(std::string_view text, int size) {
    if (!has_font()) return static_cast<int>(text.size()) * size * 6 / 10;
    return ink_of(text, size).width();
}

}  // namespace glint::detail
