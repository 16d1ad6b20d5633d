//! The connections of `footprint serve`, all on one thread that waits on them with `poll(2)`:
//! sockets are non-blocking, so no client, however slow, holds anything but its own place.
//!
//! A connection waits for a request head (all of it within [`HEAD_DEADLINE`] of the moment
//! it could start), writes the answer (at least [`MIN_RATE`] on average over the last
//! [`RATE_WINDOW`], else it is dropped), and either waits for the next head or, when it
//! closes, lingers up to [`LINGER`] reading what the client still sends, so that the answer
//! is not lost to a reset. At most [`MAX_CONNECTIONS`] are kept: a new one takes the place
//! of the oldest that is not writing an answer (idle, half-sent or lingering), else of the one
//! whose client has read nothing of its answer for longest (at least [`STALLED`]); only when
//! every place is writing an answer that its client takes is it answered 503.

use std::collections::VecDeque;
use std::io::{self, ErrorKind, IoSlice, Read, Write};
use std::net::{Shutdown, TcpListener, TcpStream};
use std::time::{Duration, Instant};

use rustix::event::{poll, PollFd, PollFlags, Timespec};

use super::http::{answer, parse_head, refusal, Parsed, Response};
use super::{Site, HEAD_DEADLINE, LINGER, MAX_CONNECTIONS, MAX_HEAD, MIN_RATE, RATE_WINDOW};

/// How often the rate of a response being written is checked.
const RATE_TICK: Duration = Duration::from_secs(1);

/// Reads of a connection's input per turn: others are served between its bursts.
const READS_PER_TURN: usize = 8;
/// New connections accepted per turn.
const ACCEPTS_PER_TURN: usize = 256;
/// The most a lingering connection may still send, bytes, before it is closed.
const LINGER_BYTES: usize = 1 << 20;
/// Connections the kernel may hold for the server before it accepts them (the standard
/// library asks for 128; a burst of idle connections beyond that would make the next
/// client's connection attempts wait a second each).
const ACCEPT_BACKLOG: i32 = 1024;
/// How long the server stops accepting when it is out of descriptors and has no place to free.
const ACCEPT_PAUSE: Duration = Duration::from_millis(100);
/// A connection whose client has taken none of its answer for this long is stalled: when
/// every place is taken, a new connection takes the place of the one stalled longest. On
/// loopback (the only address served) a client that reads never waits this long for its
/// socket; 2,000 clients that asked for the 2 MB module and read nothing held every place,
/// and the page was answered 503 until the rate check dropped them (8 s and more).
const STALLED: Duration = Duration::from_millis(250);

/// A response being written.
struct Sending<'s> {
    response: Response<'s>,
    /// Bytes of head and body written so far.
    sent: usize,
    /// When the rate is next checked.
    tick: Instant,
    /// The instants of the checks within the last [`RATE_WINDOW`] (and the start), with
    /// `sent` then, oldest first.
    marks: VecDeque<(Instant, usize)>,
    /// When the client last took bytes of it (or it started).
    progress: Instant,
}

impl Sending<'_> {
    /// Writes what the socket takes: `Ok(true)` once all of it is written, `Ok(false)` when
    /// the socket is full. Bytes taken mark progress at `now`.
    fn write_to(&mut self, mut stream: &TcpStream, now: Instant) -> io::Result<bool> {
        let head = self.response.head.as_slice();
        let body = self.response.body;
        loop {
            let written = match head.get(self.sent..) {
                Some(rest) if !rest.is_empty() => {
                    stream.write_vectored(&[IoSlice::new(rest), IoSlice::new(body)])
                }
                _ => match body.get(self.sent - head.len()..) {
                    Some(rest) if !rest.is_empty() => stream.write(rest),
                    _ => return Ok(true),
                },
            };
            match written {
                Ok(0) => return Err(ErrorKind::WriteZero.into()),
                Ok(n) => {
                    self.sent += n;
                    self.progress = now;
                }
                Err(e) if e.kind() == ErrorKind::WouldBlock => return Ok(false),
                Err(e) if e.kind() == ErrorKind::Interrupted => {}
                Err(e) => return Err(e),
            }
        }
    }
}

/// Where a connection is.
enum State<'s> {
    /// Waiting for a request head (or the rest of one).
    Head,
    /// Writing an answer.
    Send(Sending<'s>),
    /// Answered and shut for writing; reading what still comes until the client closes, or
    /// until the instant given.
    Linger(Instant, usize),
}

/// One client's connection.
struct Conn<'s> {
    stream: TcpStream,
    /// Bytes received and not yet answered: a head, the start of one, or pipelined heads.
    inbox: Vec<u8>,
    state: State<'s>,
    /// When it began to wait for its current head (accepted, or its last answer written):
    /// the head's deadline counts from here, and the oldest is evicted first.
    since: Instant,
}

impl<'s> Conn<'s> {
    fn new(stream: TcpStream, now: Instant) -> Self {
        Self {
            stream,
            inbox: Vec::new(),
            state: State::Head,
            since: now,
        }
    }

    /// What `poll` is to wait for.
    fn interest(&self) -> PollFlags {
        match self.state {
            State::Send(_) => PollFlags::OUT,
            State::Head | State::Linger(..) => PollFlags::IN,
        }
    }

    /// The next instant at which [`Conn::on_time`] has something to check.
    fn deadline(&self) -> Instant {
        match &self.state {
            State::Head => self.since + HEAD_DEADLINE,
            State::Send(s) => s.tick,
            State::Linger(until, _) => *until,
        }
    }

    /// False if the connection is to be closed now: its head is late, its lingering is over,
    /// or its client took less than [`MIN_RATE`] on average over the last [`RATE_WINDOW`] of
    /// an answer (then the connection is reset, so that the kernel drops what it still holds
    /// for it too).
    fn on_time(&mut self, site: &'s Site, now: Instant) -> bool {
        if now < self.deadline() {
            return true;
        }
        if matches!(self.state, State::Head | State::Linger(..)) {
            return false;
        }
        // Write first what the socket takes now: `poll` says a socket is writable only once a
        // good part of its buffer is free, which for a client that reads steadily can take
        // longer than a window.
        if !self.drive(site, now) {
            return false;
        }
        let State::Send(s) = &mut self.state else {
            return true;
        };
        s.tick = now + RATE_TICK;
        if let Some(&(then, sent)) = s.marks.front() {
            let span = now.duration_since(then);
            if span >= RATE_WINDOW {
                if ((s.sent - sent) as f64) < MIN_RATE as f64 * span.as_secs_f64() {
                    let linger = Some(Duration::ZERO);
                    let _ = rustix::net::sockopt::set_socket_linger(&self.stream, linger);
                    return false;
                }
                s.marks.pop_front();
            }
        }
        s.marks.push_back((now, s.sent));
        true
    }

    /// Starts writing `response`.
    fn send(&mut self, response: Response<'s>, now: Instant) {
        self.state = State::Send(Sending {
            response,
            sent: 0,
            tick: now + RATE_TICK,
            marks: VecDeque::from([(now, 0)]),
            progress: now,
        });
    }

    /// Reads, answers and writes as far as the socket allows without waiting; false if the
    /// connection is to be closed.
    fn drive(&mut self, site: &'s Site, now: Instant) -> bool {
        let mut reads = 0;
        let mut chunk = [0u8; 4096];
        loop {
            match &mut self.state {
                State::Head => match parse_head(&self.inbox) {
                    Parsed::Complete(head, n) => {
                        self.inbox.drain(..n);
                        self.send(answer(site, &head), now);
                    }
                    Parsed::TooLarge => self.send(refusal(431), now),
                    Parsed::Malformed => self.send(refusal(400), now),
                    Parsed::Partial => {
                        if reads == READS_PER_TURN {
                            return true;
                        }
                        reads += 1;
                        let room = MAX_HEAD.saturating_sub(self.inbox.len()).min(chunk.len());
                        match (&self.stream).read(chunk.get_mut(..room).unwrap_or_default()) {
                            Ok(0) => return false,
                            Ok(n) => self
                                .inbox
                                .extend_from_slice(chunk.get(..n).unwrap_or_default()),
                            Err(e) if e.kind() == ErrorKind::WouldBlock => return true,
                            Err(e) if e.kind() == ErrorKind::Interrupted => {}
                            Err(_) => return false,
                        }
                    }
                },
                State::Send(sending) => match sending.write_to(&self.stream, now) {
                    Ok(false) => return true,
                    Ok(true) if sending.response.close => {
                        let _ = self.stream.shutdown(Shutdown::Write);
                        self.inbox = Vec::new();
                        self.state = State::Linger(now + LINGER, 0);
                    }
                    Ok(true) => {
                        self.state = State::Head;
                        self.since = now;
                    }
                    Err(_) => return false,
                },
                State::Linger(_, got) => match (&self.stream).read(&mut chunk) {
                    Ok(0) => return false,
                    Ok(n) => {
                        *got += n;
                        if *got > LINGER_BYTES {
                            return false;
                        }
                    }
                    Err(e) if e.kind() == ErrorKind::WouldBlock => return true,
                    Err(e) if e.kind() == ErrorKind::Interrupted => {}
                    Err(_) => return false,
                },
            }
        }
    }
}

/// Closes the connection that has waited longest without an answer being written to it
/// (lingering ones first), else the one whose client has taken nothing of its answer for the
/// longest, if that is [`STALLED`] or more: false if every connection is writing an answer
/// that its client takes.
fn evict(conns: &mut Vec<Conn<'_>>, now: Instant) -> bool {
    let oldest = conns
        .iter()
        .enumerate()
        .filter_map(|(i, c)| match &c.state {
            State::Linger(..) => Some((0, c.since, i)),
            State::Head => Some((1, c.since, i)),
            State::Send(s) if now.duration_since(s.progress) >= STALLED => Some((2, s.progress, i)),
            State::Send(_) => None,
        })
        .min();
    match oldest {
        Some((_, _, i)) => {
            conns.swap_remove(i);
            true
        }
        None => false,
    }
}

/// Takes a new connection, making room for it if every place is taken.
fn admit<'s>(conns: &mut Vec<Conn<'s>>, stream: TcpStream, now: Instant) {
    if stream.set_nonblocking(true).is_err() {
        return;
    }
    let _ = stream.set_nodelay(true);
    if conns.len() >= MAX_CONNECTIONS && !evict(conns, now) {
        // Every place is writing an answer: a few bytes, which a new socket's buffer takes.
        let busy = refusal(503);
        let _ = (&stream).write_all(&[busy.head.as_slice(), busy.body].concat());
        return;
    }
    conns.push(Conn::new(stream, now));
}

/// Accepts what is waiting; out of descriptors, frees a place, or pauses accepting (returns
/// until when) if none can be freed.
fn accept_waiting(
    listener: &TcpListener,
    conns: &mut Vec<Conn<'_>>,
    now: Instant,
) -> Option<Instant> {
    for _ in 0..ACCEPTS_PER_TURN {
        match listener.accept() {
            Ok((stream, _)) => admit(conns, stream, now),
            Err(e) if e.kind() == ErrorKind::WouldBlock => return None,
            Err(e)
                if matches!(
                    e.kind(),
                    ErrorKind::Interrupted
                        | ErrorKind::ConnectionAborted
                        | ErrorKind::ConnectionReset
                ) => {}
            // Out of descriptors or memory.
            Err(_) => {
                if !evict(conns, now) {
                    return Some(now + ACCEPT_PAUSE);
                }
            }
        }
    }
    None
}

/// Readies a listener for [`run`]: non-blocking, with a backlog of [`ACCEPT_BACKLOG`]; done
/// before the address is printed, so that the first clients find it so.
pub(super) fn prepare(listener: &TcpListener) -> io::Result<()> {
    listener.set_nonblocking(true)?;
    // Listening again only changes the backlog (capped by the kernel's somaxconn).
    let _ = rustix::net::listen(listener, ACCEPT_BACKLOG);
    Ok(())
}

/// Serves `site` on `listener` (made ready by [`prepare`]) for ever.
pub(super) fn run(listener: &TcpListener, site: &Site) -> io::Result<()> {
    let mut conns: Vec<Conn<'_>> = Vec::new();
    let mut paused: Option<Instant> = None;
    let mut ready: Vec<PollFlags> = Vec::new();
    loop {
        let now = Instant::now();
        conns.retain_mut(|c| c.on_time(site, now));
        paused = paused.filter(|&until| now < until);
        let wake = conns.iter().map(Conn::deadline).chain(paused).min();
        let timeout = wake
            .map(|t| Timespec::try_from(t.saturating_duration_since(now)))
            .transpose()
            .map_err(|_| io::Error::other("poll timeout out of range"))?;
        // The listener first, unless accepting is paused.
        let listening = paused.is_none();
        {
            let mut fds = Vec::with_capacity(conns.len() + 1);
            if listening {
                fds.push(PollFd::new(listener, PollFlags::IN));
            }
            fds.extend(conns.iter().map(|c| PollFd::new(&c.stream, c.interest())));
            match poll(&mut fds, timeout.as_ref()) {
                Ok(_) => {}
                Err(rustix::io::Errno::INTR) => continue,
                Err(e) => return Err(e.into()),
            }
            ready.clear();
            ready.extend(fds.iter().map(PollFd::revents));
        }
        let now = Instant::now();
        let mut flags = ready.iter().skip(usize::from(listening));
        conns.retain_mut(|c| match flags.next() {
            Some(f) if !f.is_empty() => c.drive(site, now),
            _ => true,
        });
        if listening && ready.first().is_some_and(|f| !f.is_empty()) {
            paused = accept_waiting(listener, &mut conns, now);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::net::Ipv4Addr;

    #[test]
    fn eviction_takes_lingering_then_the_oldest_idle_then_a_stalled_answer() {
        let listener = TcpListener::bind((Ipv4Addr::LOCALHOST, 0)).unwrap();
        let addr = listener.local_addr().unwrap();
        let t0 = Instant::now();
        let mut clients = Vec::new();
        let mut conns = Vec::new();
        // Oldest first: one being answered, two idle, one lingering.
        for (i, kind) in ["send", "head", "head", "linger"].into_iter().enumerate() {
            clients.push(TcpStream::connect(addr).unwrap());
            let (stream, _) = listener.accept().unwrap();
            let since = t0 + Duration::from_secs(i as u64);
            let mut conn = Conn::new(stream, since);
            match kind {
                "send" => conn.send(refusal(503), since),
                "linger" => conn.state = State::Linger(since + LINGER, 0),
                _ => {}
            }
            conns.push(conn);
        }
        let left = |conns: &Vec<Conn<'_>>| {
            let mut s: Vec<u64> = conns
                .iter()
                .map(|c| c.since.duration_since(t0).as_secs())
                .collect();
            s.sort_unstable();
            s
        };
        // The answer started at t0 and its client has taken nothing since.
        let taking = t0 + STALLED / 2;
        assert!(evict(&mut conns, taking));
        assert_eq!(left(&conns), [0, 1, 2], "the lingering one first");
        assert!(evict(&mut conns, taking));
        assert_eq!(left(&conns), [0, 2], "then the oldest idle one");
        assert!(evict(&mut conns, taking));
        assert_eq!(left(&conns), [0]);
        assert!(
            !evict(&mut conns, taking),
            "never one being answered, within STALLED of its last progress"
        );
        assert_eq!(conns.len(), 1);
        // Issue 54, item 10: one whose client has read nothing for STALLED or more.
        assert!(evict(&mut conns, t0 + STALLED), "a stalled answer");
        assert!(conns.is_empty());
    }
}
