"""Read the material point positions of one output frame (a .pvtu and its
.vtu pieces) without VTK. dealii-mpm writes the points with their data
appended, zlib-compressed, with UInt64 headers (one piece per rank);
deal.II's own writer (the grid) writes inline binary, zlib-compressed with
UInt32 headers: both (and raw appended data) are read. Used by the
benchmark scripts.

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


def _appended_bytes(data, offset, compressed):
    """The bytes of an appended DataArray at @p offset of the appended
    section (UInt64 headers): raw, a byte count and the values; compressed,
    the number of blocks, the block size, the last block's size and the
    compressed size of each block, then the blocks."""
    if not compressed:
        n = struct.unpack("<Q", data[offset:offset + 8])[0]
        return data[offset + 8:offset + 8 + n]
    n_blocks = struct.unpack("<Q", data[offset:offset + 8])[0]
    sizes = struct.unpack("<%dQ" % n_blocks,
                          data[offset + 24:offset + 24 + 8 * n_blocks])
    out, at = b"", offset + 24 + 8 * n_blocks
    for size in sizes:
        out += zlib.decompress(data[at:at + size])
        at += size
    return out


def _appended(data, offset, kind, n_components, compressed):
    raw = _appended_bytes(data, offset, compressed)
    fmt, size = ("f", 4) if kind == "Float32" else ("d", 8)
    values = struct.unpack("<%d%s" % (len(raw) // size, fmt), raw)
    return [values[i:i + n_components]
            for i in range(0, len(values), n_components)]


def _read(path):
    """The XML part of a .vtu and its appended raw data (b"" if none)."""
    raw = open(path, "rb").read()
    marker = raw.find(b"<AppendedData")
    if marker < 0:
        return raw.decode(), b""
    start = raw.index(b"_", marker) + 1
    return raw[:start].decode(), raw[start:]


def _arrays(path, pattern):
    """The tuples of every DataArray whose opening tag matches @p pattern
    (groups: type, number of components, then the tag's rest)."""
    xml, data = _read(path)
    out, found = [], False
    for m in re.finditer(pattern, xml, re.S):
        kind, n = m.group(1), int(m.group(2) or 1)
        found = True
        appended = re.search(r'format="appended" offset="(\d+)"', m.group(0))
        if appended:
            out += _appended(data, int(appended.group(1)), kind, n,
                             "compressor=" in xml)
        else:
            body = xml[m.end():xml.index("</DataArray>", m.end())]
            out += _tuples(kind, body, n)
    return out, found


def read_vtu_points(path):
    """Every <Piece> of the file."""
    xml, data = _read(path)
    points = []
    for m in re.finditer(r'<Points>\s*(<DataArray[^>]*type="(Float32|Float64)"'
                         r'[^>]*>)', xml, re.S):
        appended = re.search(r'format="appended" offset="(\d+)"', m.group(1))
        if appended:
            points += _appended(data, int(appended.group(1)), m.group(2), 3,
                                "compressor=" in xml)
        else:
            body = xml[m.end():xml.index("</DataArray>", m.end())]
            points += _tuples(m.group(2), body, 3)
    return points


def read_vtu_field(path, name):
    values, found = _arrays(path, r'<DataArray type="(Float32|Float64)" Name="%s"'
                            r'(?: NumberOfComponents="(\d+)")?[^>]*>'
                            % re.escape(name))
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
