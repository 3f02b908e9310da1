//! Contact islands: the 4-connected groups of cells in contact (cells sharing a side, not
//! only a corner), counted by a flood fill.

/// The number of 4-connected groups of `true` cells in the `nx`-wide row-major `mask`.
pub fn count_islands(mask: &[bool], nx: usize) -> usize {
    let ny = mask.len() / nx.max(1);
    let mut seen = vec![false; mask.len()];
    let mut stack = Vec::new();
    let mut islands = 0;
    for start in 0..mask.len() {
        if !mask[start] || seen[start] {
            continue;
        }
        islands += 1;
        seen[start] = true;
        stack.push(start);
        while let Some(i) = stack.pop() {
            let (ix, iy) = (i % nx, i / nx);
            let neighbours = [
                (ix > 0).then(|| i - 1),
                (ix + 1 < nx).then(|| i + 1),
                (iy > 0).then(|| i - nx),
                (iy + 1 < ny).then(|| i + nx),
            ];
            for j in neighbours.into_iter().flatten() {
                if mask[j] && !seen[j] {
                    seen[j] = true;
                    stack.push(j);
                }
            }
        }
    }
    islands
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn sides_connect_corners_do_not() {
        let rows = ["##..#", "#...#", "..#..", ".#.##"];
        let mask: Vec<bool> = rows
            .iter()
            .flat_map(|r| r.chars().map(|c| c == '#'))
            .collect();
        // {(0,0),(1,0),(0,1)}, {(4,0),(4,1)}, {(2,2)}, {(1,3)}, {(3,3),(4,3)}: the corner
        // contacts (2,2)-(1,3) and (2,2)-(3,3) do not join.
        assert_eq!(count_islands(&mask, 5), 5);
        assert_eq!(count_islands(&[false; 6], 3), 0);
        assert_eq!(count_islands(&[true; 6], 3), 1);
    }
}
