"""Read the material point positions of one output frame (a .pvtu and its
.vtu pieces, as dealii-mpm writes them: binary, zlib-compressed, UInt32
headers) without VTK. Used by the benchmark scripts.

    from vtu_points import read_points
    xyz = read_points("output/particles_00015.pvtu")   # list of (x, y, z)
"""
import base64, os, re, struct, zlib


def _decode(text):
    """One zlib-compressed binary DataArray: a header of UInt32 (number of
    blocks, block size, last block size, compressed sizes), then the
    blocks, each base64-encoded on its own."""
    text = text.strip()
    first = base64.b64decode(text[:8])  # 6 bytes: enough for n_blocks
    n_blocks = struct.unpack("<I", first[:4])[0]
    header_bytes = 4 * (3 + n_blocks)
    header_chars = 4 * ((header_bytes + 2) // 3)
    header = struct.unpack("<%dI" % (3 + n_blocks),
                           base64.b64decode(text[:header_chars])[:header_bytes])
    data = base64.b64decode(text[header_chars:])
    out, offset = b"", 0
    for size in header[3:]:
        out += zlib.decompress(data[offset:offset + size])
        offset += size
    return out


def read_vtu_points(path):
    xml = open(path).read()
    m = re.search(r"<Points>\s*<DataArray[^>]*type=\"(Float32|Float64)\"[^>]*>"
                  r"(.*?)</DataArray>", xml, re.S)
    kind, text = m.group(1), m.group(2)
    raw = _decode(text)
    fmt, size = ("f", 4) if kind == "Float32" else ("d", 8)
    values = struct.unpack("<%d%s" % (len(raw) // size, fmt), raw)
    return [values[i:i + 3] for i in range(0, len(values), 3)]


def read_points(pvtu):
    directory = os.path.dirname(pvtu)
    pieces = re.findall(r"<Piece\s+Source=\"([^\"]+)\"", open(pvtu).read())
    points = []
    for piece in pieces:
        points += read_vtu_points(os.path.join(directory, piece))
    return points
