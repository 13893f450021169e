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
   ULOG_MESSAGE_TYPES
   DATAFLASH_HEADER
"""

from __future__ import annotations

import numpy as np
from numba import njit

__all__ = ["walk_ulog", "walk_dataflash", "gather", "ULOG_MESSAGE_TYPES", "DATAFLASH_HEADER"]

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
