#include "mesh/checksum.h"

#include "mesh/error.h"

#include <openssl/evp.h>

#include <fstream>
#include <memory>
#include <vector>

namespace glint {

namespace {

struct Digest {
    std::unique_ptr<EVP_MD_CTX, decltype(&EVP_MD_CTX_free)> ctx{EVP_MD_CTX_new(), &EVP_MD_CTX_free};
    Digest() {
        if (!ctx || EVP_DigestInit_ex(ctx.get(), EVP_sha256(), nullptr) != 1)
            throw IoError("SHA-256: cannot create a digest context");
    }
    void add(const char* data, std::size_t size) { EVP_DigestUpdate(ctx.get(), data, size); }
    std::string hex() {
        unsigned char digest[EVP_MAX_MD_SIZE];
        unsigned int len = 0;
        EVP_DigestFinal_ex(ctx.get(), digest, &len);
        static constexpr char kHex[] = "0123456789abcdef";
        std::string text(2 * std::size_t{len}, '0');
        for (unsigned int i = 0; i < len; ++i) {
            text[2 * i] = kHex[digest[i] >> 4];
            text[2 * i + 1] = kHex[digest[i] & 15];
        }
        return text;
    }
};

}  // namespace

std::string sha256_hex(std::span<const char> bytes) {
    Digest d;
    d.add(bytes.data(), bytes.size());
    return d.hex();
}

std::string sha256_file(const std::filesystem::path& path) {
    std::ifstream in(path, std::ios::binary);
    if (!in) throw IoError("cannot read \"" + path.string() + "\" to checksum it");
    Digest d;
    std::vector<char> buf(std::size_t{1} << 16);
    while (in) {
        in.read(buf.data(), static_cast<std::streamsize>(buf.size()));
        d.add(buf.data(), static_cast<std::size_t>(in.gcount()));
    }
    return d.hex();
}

}  // namespace glint
