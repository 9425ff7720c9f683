"""Read the material point positions of one output frame (a .pvtu and its
.vtu pieces, as dealii-mpm writes them: binary, zlib-compressed, UInt32
headers) without VTK. Used by the benchmark scripts.

    from vtu_points import read_points
    xyz = read_points("output/particles_00015.pvtu")   # list of (x, y, z)
    s = read_field("output/particles_00015.pvtu", "stress")  # tuples
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


def _tuples(kind, text, n_components):
    raw = _decode(text)
    fmt, size = ("f", 4) if kind == "Float32" else ("d", 8)
    values = struct.unpack("<%d%s" % (len(raw) // size, fmt), raw)
    return [values[i:i + n_components]
            for i in range(0, len(values), n_components)]


def read_vtu_points(path):
    """Every <Piece> of the file: a run on several ranks writes one piece
    per rank into the same .vtu."""
    xml = open(path).read()
    points = []
    for m in re.finditer(r"<Points>\s*<DataArray[^>]*type=\"(Float32|Float64)\"[^>]*>"
                         r"(.*?)</DataArray>", xml, re.S):
        points += _tuples(m.group(1), m.group(2), 3)
    return points


def read_vtu_field(path, name):
    xml = open(path).read()
    values, found = [], False
    for m in re.finditer(r"<DataArray type=\"(Float32|Float64)\" Name=\"%s\""
                         r"(?: NumberOfComponents=\"(\d+)\")?[^>]*>(.*?)</DataArray>"
                         % re.escape(name), xml, re.S):
        values += _tuples(m.group(1), m.group(3), int(m.group(2) or 1))
        found = True
    if not found:
        raise KeyError("no field '%s' in %s" % (name, path))
    return values


def _pieces(pvtu):
    directory = os.path.dirname(pvtu)
    return [os.path.join(directory, piece) for piece in
            re.findall(r"<Piece\s+Source=\"([^\"]+)\"", open(pvtu).read())]


def read_points(pvtu):
    points = []
    for piece in _pieces(pvtu):
        points += read_vtu_points(piece)
    return points


def read_field(pvtu, name):
    """The values of point field @p name, in the order of read_points."""
    values = []
    for piece in _pieces(pvtu):
        values += read_vtu_field(piece, name)
    return values
