"""The records of a binary log: where each message starts, how long it is, what kind it is.

ULog and DataFlash logs are streams of variable-length records: a record's
length is in its own header (ULog) or in a format message read earlier
(DataFlash), so the start of a record is known only once every record before
it has been read.  That walk cannot be vectorised; it is compiled once
(numba, cached on disk) and runs at memory speed, where a Python loop over the
3.6 million records of an hour at 1 kHz takes tens of seconds.  The walk
returns the offsets; the fields are then read with numpy, one message type at
a time (:func:`gather`).

The file is walked in chunks (:func:`walk_ulog` and :func:`walk_dataflash`
take a start offset and return the offset of the first record they could not
finish), so memory stays bounded whatever the size of the log.

Public API
----------
.. autosummary::

   walk_ulog
   walk_dataflash
   gather
   extract_ulog
   scan_ulog
   ULOG_MESSAGE_TYPES
   DATAFLASH_HEADER
"""

from __future__ import annotations

import numpy as np
from numba import njit

__all__ = ["walk_ulog", "walk_dataflash", "gather", "extract_ulog", "scan_ulog", "FIELD_TYPES", "ULOG_MESSAGE_TYPES", "DATAFLASH_HEADER"]

#: Field types :func:`extract_ulog` reads (little-endian), by code.
FIELD_TYPES = ("<f4", "<u4", "<u2", "<u8", "<f8", "<i4", "<i8")

#: The ULog message types (the third byte of a record header) of the ULog specification
#: (docs.px4.io, "ULog File Format"): F, I, M, P, Q, A, R, D, L, C, S, O, B.
ULOG_MESSAGE_TYPES = b"FIMPQARDLCSOB"

#: The two bytes that open every DataFlash record (ArduPilot ``HEAD_BYTE1``, ``HEAD_BYTE2``).
DATAFLASH_HEADER = (0xA3, 0x95)

_ULOG_KNOWN = np.zeros(256, dtype=np.bool_)
_ULOG_KNOWN[np.frombuffer(ULOG_MESSAGE_TYPES, dtype=np.uint8)] = True


@njit(cache=True)
def _walk_ulog(buf, start, known, offsets, sizes, kinds):  # pragma: no cover - compiled
    n = buf.size
    pos = start
    count = 0
    cap = offsets.size
    bad = -1
    while pos + 3 <= n and count < cap:
        size = np.int64(buf[pos]) | (np.int64(buf[pos + 1]) << 8)
        kind = buf[pos + 2]
        if size == 0 or not known[kind]:
            bad = pos
            break
        if pos + 3 + size > n:
            break
        offsets[count] = pos
        sizes[count] = size
        kinds[count] = kind
        count += 1
        pos += 3 + size
    return count, pos, bad


def walk_ulog(buf: np.ndarray, start: int, *, capacity: int = 1 << 20):
    """The ULog records of ``buf`` from ``start``: offsets, payload sizes and types.

    Parameters
    ----------
    buf : ndarray of uint8
        Bytes of the data section (or a chunk of it).
    start : int
        Offset of the first record header in ``buf`` [bytes].
    capacity : int, keyword-only
        Most records returned by one call [count] (bounds the memory).

    Returns
    -------
    offsets : ndarray of int64
        Offset of each record header in ``buf`` [bytes].
    sizes : ndarray of int64
        Payload size of each record (after the three header bytes) [bytes].
    kinds : ndarray of uint8
        Message type of each record (``ord('D')`` for data).
    next_offset : int
        Offset of the first record not returned: incomplete in ``buf``, or past ``capacity``.
    corrupt_at : int
        Offset of a header with size 0 or an unknown type (the walk stops there), or -1.

    References
    ----------
    PX4 documentation, "ULog File Format": message header ``uint16_t msg_size; uint8_t msg_type``.
    """
    offsets = np.empty(capacity, dtype=np.int64)
    sizes = np.empty(capacity, dtype=np.int64)
    kinds = np.empty(capacity, dtype=np.uint8)
    count, pos, bad = _walk_ulog(buf, np.int64(start), _ULOG_KNOWN, offsets, sizes, kinds)
    return offsets[:count], sizes[:count], kinds[:count], int(pos), int(bad)


@njit(cache=True)
def _walk_dataflash(buf, start, lengths, offsets, kinds):  # pragma: no cover - compiled
    n = buf.size
    pos = start
    count = 0
    cap = offsets.size
    skipped = 0
    while pos + 3 <= n and count < cap:
        if buf[pos] != 0xA3 or buf[pos + 1] != 0x95:
            pos += 1
            skipped += 1
            continue
        kind = buf[pos + 2]
        length = lengths[kind]
        if length <= 0:  # a type without a format yet: return to read it (FMT is 128)
            if kind == 128:
                length = 89
            else:
                pos += 1
                skipped += 1
                continue
        if pos + length > n:
            break
        offsets[count] = pos
        kinds[count] = kind
        count += 1
        pos += length
        if kind == 128:  # a format message: the caller reads it before the walk goes on
            break
    return count, pos, skipped


def walk_dataflash(buf: np.ndarray, start: int, lengths: np.ndarray, *, capacity: int = 1 << 20):
    """The DataFlash records of ``buf`` from ``start``, stopping after each format (FMT) record.

    Parameters
    ----------
    buf : ndarray of uint8
        Bytes of the log (or a chunk of it).
    start : int
        Offset to start from [bytes].
    lengths : ndarray of int64, shape (256,)
        Record length (header included) of each message type known so far, 0 for unknown [bytes].
    capacity : int, keyword-only
        Most records returned by one call [count].

    Returns
    -------
    offsets : ndarray of int64
        Offset of each record in ``buf`` [bytes].
    kinds : ndarray of uint8
        Message type of each record.
    next_offset : int
        Offset where the walk stopped (after a FMT record, at an incomplete record, or at ``capacity``).
    skipped : int
        Bytes skipped that did not start a known record [bytes].

    References
    ----------
    ArduPilot ``libraries/AP_Logger/LogStructure.h``: ``LOG_PACKET_HEADER`` (0xA3, 0x95, type) and
    ``log_Format`` (type 128, 89 bytes: type, length, name[4], format[16], labels[64]).
    """
    offsets = np.empty(capacity, dtype=np.int64)
    kinds = np.empty(capacity, dtype=np.uint8)
    count, pos, skipped = _walk_dataflash(buf, np.int64(start), np.asarray(lengths, dtype=np.int64), offsets, kinds)
    return offsets[:count], kinds[:count], int(pos), int(skipped)


@njit(cache=True)
def _gather(buf, offsets, width, out):  # pragma: no cover - compiled
    for i in range(offsets.size):
        o = offsets[i]
        for j in range(width):
            out[i, j] = buf[o + j]


def gather(buf: np.ndarray, offsets: np.ndarray, width: int) -> np.ndarray:
    """The ``width`` bytes at each of ``offsets``, as rows of a ``(len(offsets), width)`` uint8 array.

    View the result with a structured dtype of itemsize ``width`` to read the fields.

    Parameters
    ----------
    buf : ndarray of uint8
        Bytes.
    offsets : ndarray of int64
        Start of each record's fields in ``buf`` [bytes].
    width : int
        Bytes per record [bytes].

    Returns
    -------
    ndarray of uint8, shape (len(offsets), width)
    """
    out = np.empty((offsets.size, int(width)), dtype=np.uint8)
    if offsets.size:
        _gather(buf, np.asarray(offsets, dtype=np.int64), int(width), out)
    return out


@njit(cache=True)
def _extract_ulog(buf, offsets, sizes, kinds, msg_id, min_size, field_offsets, field_codes, out, start):  # pragma: no cover - compiled
    s2, s4, s8 = np.zeros(2, np.uint8), np.zeros(4, np.uint8), np.zeros(8, np.uint8)
    f4, u4, i4, u2 = s4.view(np.float32), s4.view(np.uint32), s4.view(np.int32), s2.view(np.uint16)
    u8, f8, i8 = s8.view(np.uint64), s8.view(np.float64), s8.view(np.int64)
    k = start
    n_out = out.shape[0]
    n_fields = field_offsets.size
    for r in range(offsets.size):
        if kinds[r] != 68 or sizes[r] < min_size or k >= n_out:
            continue
        o = offsets[r]
        if (np.int64(buf[o + 3]) | (np.int64(buf[o + 4]) << 8)) != msg_id:
            continue
        base = o + 5
        for j in range(n_fields):
            at = base + field_offsets[j]
            code = field_codes[j]
            if code == 2:
                s2[0], s2[1] = buf[at], buf[at + 1]
                out[k, j] = u2[0]
            elif code == 0 or code == 1 or code == 5:
                for i in range(4):
                    s4[i] = buf[at + i]
                out[k, j] = f4[0] if code == 0 else (u4[0] if code == 1 else i4[0])
            else:
                for i in range(8):
                    s8[i] = buf[at + i]
                out[k, j] = u8[0] if code == 3 else (f8[0] if code == 4 else i8[0])
        k += 1
    return k


def extract_ulog(buf: np.ndarray, offsets, sizes, kinds, msg_id: int, min_size: int, field_offsets, field_codes, out: np.ndarray, start: int) -> int:
    """Read the fields of one subscription's data records straight into rows of ``out`` (float64).

    Parameters
    ----------
    buf : ndarray of uint8
        The chunk of the file.
    offsets, sizes, kinds : ndarray
        The records of the chunk (:func:`walk_ulog`).
    msg_id : int
        The subscription whose records are read.
    min_size : int
        Smallest payload accepted (the format's size plus the two bytes of the id) [bytes].
    field_offsets : ndarray of int64
        Offset of each field after the id [bytes].
    field_codes : ndarray of int64
        Type of each field, an index into :data:`FIELD_TYPES`.
    out : ndarray of float64, shape (N, len(field_offsets))
        Rows to fill.
    start : int
        First row to fill.

    Returns
    -------
    int
        The next row to fill (rows beyond ``out`` are dropped).
    """
    return int(_extract_ulog(buf, offsets, sizes, kinds, np.int64(msg_id), np.int64(min_size), np.asarray(field_offsets, dtype=np.int64),
                             np.asarray(field_codes, dtype=np.int64), out, np.int64(start)))  # fmt: skip


@njit(cache=True)
def _scan_ulog(buf, offsets, sizes, kinds, t_offset, min_size, tallies):  # pragma: no cover - compiled
    short = 0
    for r in range(offsets.size):
        if kinds[r] != 68:
            continue
        o = offsets[r]
        m = np.int64(buf[o + 3]) | (np.int64(buf[o + 4]) << 8)
        if t_offset[m] < 0:
            tallies[0, m] += 1
            continue
        if sizes[r] < min_size[m]:
            short += 1
            continue
        at = o + 5 + t_offset[m]
        ts = np.int64(0)
        for i in range(8):
            ts |= np.int64(buf[at + i]) << np.int64(8 * i)
        if tallies[0, m] == 0:
            tallies[1, m] = ts
        tallies[2, m] = ts
        tallies[0, m] += 1
    return short


def scan_ulog(buf: np.ndarray, offsets, sizes, kinds, t_offset, min_size, tallies) -> int:
    """Count the data records of each subscription and note their first and last timestamps.

    Parameters
    ----------
    buf : ndarray of uint8
        The chunk.
    offsets, sizes, kinds : ndarray
        Its records (:func:`walk_ulog`).
    t_offset : ndarray of int64, shape (65536,)
        Per message id, the offset of its ``timestamp`` after the id, or a negative number
        where the format has none (its records are counted only) [bytes].
    min_size : ndarray of int64, shape (65536,)
        Per message id, the smallest payload of a whole record [bytes].
    tallies : ndarray of int64, shape (3, 65536)
        Records, first and last timestamp per message id, updated in place.

    Returns
    -------
    int
        Records shorter than their format (not counted) [count].
    """
    return int(_scan_ulog(buf, offsets, sizes, kinds, t_offset, min_size, tallies))
